#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Every invocation adds (x % 4 + 1) to bin (x % width, 0) of an r32ui image and takes max/min of its id.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint count; uint bins; } params;
BL_IMAGE(0, r32ui) uniform uimage2D bins;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    int b = int(i % params.bins);
    imageAtomicAdd(bins, ivec2(b, 0), i % 4u + 1u);
    imageAtomicMax(bins, ivec2(b, 1), i);
    imageAtomicMin(bins, ivec2(b, 2), i);
    imageAtomicOr(bins, ivec2(b, 3), 1u << (i % 32u));
}
