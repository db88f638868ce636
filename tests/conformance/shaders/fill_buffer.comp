#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Writes out[i] = i * scale + offset for i < count.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params {
    uint count;
    uint scale;
    uint offset;
} params;
BL_STORAGE_BUFFER(0) Output {
    uint values[];
} outBuf;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < params.count) outBuf.values[i] = i * params.scale + params.offset;
}
