#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
// Mid level (4³ nodes of 16³ voxels) and root of each changed cascade's tree: one group per cascade,
// one thread per mid node; float boxes in logical voxel units.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint cascadeMask; } params;
BL_STORAGE_BUFFER(0) Trees { uint trees[]; };

shared vec3 midMin[64], midMax[64];

void main() {
    uint cascade = gl_WorkGroupID.y;
    if ((params.cascadeMask & (1u << cascade)) == 0u) return;
    uint m = gl_LocalInvocationIndex;
    ivec3 mid = ivec3(m & 3u, (m >> 2) & 3u, m >> 4);
    uint base = cascade * BL_SDF_TREE_STRIDE;
    vec3 lo = vec3(1e30), hi = vec3(-1e30);
    for (int i = 0; i < 64; ++i) {
        ivec3 b = mid * 4 + ivec3(i & 3, (i >> 2) & 3, i >> 4);
        uint bits = trees[base + uint((b.z * 16 + b.y) * 16 + b.x)];
        if (bits == BL_SDF_NODE_EMPTY) continue;
        vec3 nmin = vec3(uvec3(bits, bits >> 5, bits >> 10) & 31u);
        vec3 nmax = vec3(uvec3(bits >> 15, bits >> 20, bits >> 25) & 31u);
        lo = min(lo, vec3(b * 4) + nmin / 7.0);
        hi = max(hi, vec3(b * 4) + nmax / 7.0);
    }
    midMin[m] = lo;
    midMax[m] = hi;
    uint at = base + BL_SDF_TREE_MID + 8u * m;
    trees[at + 0u] = floatBitsToUint(lo.x);
    trees[at + 1u] = floatBitsToUint(lo.y);
    trees[at + 2u] = floatBitsToUint(lo.z);
    trees[at + 4u] = floatBitsToUint(hi.x);
    trees[at + 5u] = floatBitsToUint(hi.y);
    trees[at + 6u] = floatBitsToUint(hi.z);
    barrier();
    if (m != 0u) return;
    for (uint i = 1u; i < 64u; ++i) {
        lo = min(lo, midMin[i]);
        hi = max(hi, midMax[i]);
    }
    at = base + BL_SDF_TREE_ROOT;
    trees[at + 0u] = floatBitsToUint(lo.x);
    trees[at + 1u] = floatBitsToUint(lo.y);
    trees[at + 2u] = floatBitsToUint(lo.z);
    trees[at + 4u] = floatBitsToUint(hi.x);
    trees[at + 5u] = floatBitsToUint(hi.y);
    trees[at + 6u] = floatBitsToUint(hi.z);
}
