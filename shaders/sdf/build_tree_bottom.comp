#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
// Bottom level of each changed cascade's AABB tree: one thread per node of 4³ voxels (16³ nodes), in
// logical (scrolled) coordinates. Unbuilt voxels count as full so that rays find them and fall back.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint cascadeMask; } params;
BL_READ_BUFFER(0) CascadeTable { BL_SDF_CASCADE_TABLE_BODY } table;
BL_READ_BUFFER(1) BrickMaps { uint brickMaps[]; };
BL_READ_BUFFER(2) BrickAabbs { uint brickAabbs[]; };
BL_STORAGE_BUFFER(0) Trees { uint trees[]; };

void main() {
    uint cascade = gl_WorkGroupID.y;
    if ((params.cascadeMask & (1u << cascade)) == 0u) return;
    uint node = gl_GlobalInvocationID.x;
    ivec3 n = ivec3(node % 16u, (node / 16u) % 16u, node / 256u);
    ivec3 origin = table.cascades[cascade].origin.xyz;
    uvec3 lo = uvec3(31u), hi = uvec3(0u);
    for (int i = 0; i < 64; ++i) {
        ivec3 local = ivec3(i & 3, (i >> 2) & 3, i >> 4);
        uint state = brickMaps[cascade * BL_SDF_CASCADE_VOXELS + blSdfPhysicalIndex(origin + n * 4 + local)];
        if (state == BL_SDF_EMPTY) continue;
        uvec3 vmin = uvec3(local * 7), vmax = vmin + 7u;
        if (state < BL_SDF_FIRST_STATE) {
            uint aabb = brickAabbs[state];
            if (aabb == BL_SDF_AABB_NONE) continue;
            vmax = vmin + blSdfAabbMax(aabb);
            vmin += blSdfAabbMin(aabb);
        }
        lo = min(lo, vmin);
        hi = max(hi, vmax);
    }
    uint bits = BL_SDF_NODE_EMPTY;
    if (lo.x <= hi.x) bits = lo.x | (lo.y << 5) | (lo.z << 10) | (hi.x << 15) | (hi.y << 20) | (hi.z << 25);
    trees[cascade * BL_SDF_TREE_STRIDE + node] = bits;
}
