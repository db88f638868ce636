#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// GL smoke test: out[i] = 2 * in[i] (a reader of a buffer another dispatch wrote).
layout(local_size_x = 64) in;
BL_READ_BUFFER(0) Input {
    uint values[];
} inBuf;
BL_STORAGE_BUFFER(0) Output {
    uint values[];
} outBuf;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < inBuf.values.length()) outBuf.values[i] = 2u * inBuf.values[i];
}
