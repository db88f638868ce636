#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
// One thread per stored reference: writes the triangle into its voxel's range of the sorted list.
layout(local_size_x = 64) in;
BL_READ_BUFFER(0) References { uint references[]; };
BL_READ_BUFFER(1) VoxelRefs { uint voxelRefs[]; };
BL_READ_BUFFER(2) Touched { uvec4 touched[]; };
BL_READ_BUFFER(3) Counters { uint counters[]; };
BL_STORAGE_BUFFER(0) SortedReferences { uint sortedReferences[]; };

void main() {
    uint r = gl_GlobalInvocationID.y * (BL_SDF_WIDE_GROUPS * 64u) + gl_GlobalInvocationID.x;
    if (r >= counters[C_REFS_STORED]) return;
    uint key = references[3u * r];
    uvec4 entry = touched[voxelRefs[2u * key + 1u]];
    if (entry.w == BL_SDF_UNBUILT) return;  // the voxel got no brick
    sortedReferences[entry.z + references[3u * r + 2u]] = references[3u * r + 1u];
}
