#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Reads a buffer and accumulates its sum with an atomic into a result buffer (used for read-after-read).
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint count; } params;
BL_READ_BUFFER(0) Source { uint src[]; } source;
BL_STORAGE_BUFFER(0) Result { uint sum; } result;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < params.count) atomicAdd(result.sum, source.src[i]);
}
