#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Samples a 2D texture at (u, v, lod) coordinates read from a buffer: exercises samplers and mip views.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint count; } params;
BL_TEXTURE(0) uniform sampler2D source;
BL_READ_BUFFER(0) Coords { vec4 coords[]; } coordsBuf;
BL_STORAGE_BUFFER(0) Output { vec4 values[]; } outBuf;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    vec4 c = coordsBuf.coords[i];
    outBuf.values[i] = textureLod(source, c.xy, c.z);
}
