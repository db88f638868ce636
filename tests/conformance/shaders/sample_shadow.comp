#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Depth comparison sampling at (u, v, reference) read from a buffer.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint count; } params;
BL_TEXTURE(0) uniform sampler2DShadow depthTex;
BL_READ_BUFFER(0) Coords { vec4 coords[]; } coordsBuf;
BL_STORAGE_BUFFER(0) Output { float values[]; } outBuf;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    outBuf.values[i] = texture(depthTex, coordsBuf.coords[i].xyz);
}
