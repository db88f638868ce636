#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Buffer atomics: sums, max, min, xor and compare-exchange counters over `count` invocations.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint count; } params;
BL_STORAGE_BUFFER(0) Counters { uint sum; uint maxv; uint minv; uint xorv; uint exchanged; uint perBin[16]; } c;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    atomicAdd(c.sum, i);
    atomicMax(c.maxv, i * 7u);
    atomicMin(c.minv, i + 5u);
    atomicXor(c.xorv, i);
    atomicCompSwap(c.exchanged, 0u, 1u);
    atomicAdd(c.perBin[i % 16u], 1u);
}
