#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Two constants blocks with std140 padding rules (vec3 + float, arrays of scalars, mat4) copied to a buffer.
layout(local_size_x = 1) in;
BL_CONSTANTS(0) uniform First { vec3 a; float b; uvec2 c; int d; float e[3]; mat4 m; } first;
BL_CONSTANTS(1) uniform Second { vec4 scale; uint tag; } second;
BL_STORAGE_BUFFER(0) Output { float values[]; } outBuf;
void main() {
    outBuf.values[0] = first.a.x; outBuf.values[1] = first.a.y; outBuf.values[2] = first.a.z;
    outBuf.values[3] = first.b;
    outBuf.values[4] = float(first.c.x); outBuf.values[5] = float(first.c.y);
    outBuf.values[6] = float(first.d);
    outBuf.values[7] = first.e[0]; outBuf.values[8] = first.e[1]; outBuf.values[9] = first.e[2];
    vec4 v = first.m * second.scale;
    outBuf.values[10] = v.x; outBuf.values[11] = v.y; outBuf.values[12] = v.z; outBuf.values[13] = v.w;
    outBuf.values[14] = float(second.tag);
}
