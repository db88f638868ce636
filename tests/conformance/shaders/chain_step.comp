#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// One link of a dependency chain: dst[i] = src[i] * 2 + step (a missed barrier changes the result).
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint count; uint step; } params;
BL_READ_BUFFER(0) Source { uint src[]; } source;
BL_STORAGE_BUFFER(0) Dest { uint dst[]; } dest;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < params.count) dest.dst[i] = source.src[i] * 2u + params.step;
}
