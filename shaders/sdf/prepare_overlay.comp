#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
// First pass of an update's overlay round (the voxels a dynamic instance's old or new footprint reaches),
// one thread per overlay job voxel. The voxel's static field is kept aside as its base: its live brick (or
// EMPTY) moves to the base map if it has none yet; a live brick that was a composite of an earlier update
// goes back to the free list. The voxel then builds again (BUILDING) from the dynamic triangles alone, and the
// brick pass takes the minimum with the base. A voxel whose static field is not built (UNBUILT, no base) is
// left alone: rays fall to the next cascade there until a full job builds it.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint jobCount; uint voxelCount; } params;
BL_READ_BUFFER(0) JobTable { BL_SDF_JOB_TABLE_BODY } jobTable;
BL_STORAGE_BUFFER(0) BrickMaps { uint brickMaps[]; };
BL_STORAGE_BUFFER(1) VoxelRefs { uint voxelRefs[]; };  // [2 * key] count, [2 * key + 1] touched index
BL_STORAGE_BUFFER(2) FreeStack { uint freeStack[]; };
BL_STORAGE_BUFFER(3) Counters { uint counters[]; };
BL_STORAGE_BUFFER(4) BaseMaps { uint baseMaps[]; };
#include "job_lookup.glsl"

void main() {
    uint index = gl_GlobalInvocationID.y * (BL_SDF_WIDE_GROUPS * 64u) + gl_GlobalInvocationID.x;
    if (index >= params.voxelCount) return;
    ivec3 voxel;
    uint cascade;
    blSdfJobVoxel(index, params.jobCount, voxel, cascade);
    uint key = cascade * BL_SDF_CASCADE_VOXELS + blSdfPhysicalIndex(voxel);
    // Overlay jobs may overlap: one thread per voxel takes it (BUILDING marks it taken).
    uint live = atomicExchange(brickMaps[key], BL_SDF_BUILDING);
    if (live == BL_SDF_BUILDING) return;
    uint base = baseMaps[key];
    if (base == BL_SDF_NO_BASE) {
        if (live == BL_SDF_UNBUILT) {
            brickMaps[key] = BL_SDF_UNBUILT;
            return;
        }
        baseMaps[key] = live;
    } else if (live < BL_SDF_FIRST_STATE) {
        uint slot = atomicAdd(counters[C_FREE_COUNT], 1u);
        freeStack[slot] = live;
        atomicAdd(counters[C_BRICKS_FREED], 1u);
    }
    voxelRefs[2u * key] = 0u;
}
