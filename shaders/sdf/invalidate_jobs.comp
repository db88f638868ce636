#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
// Pass 1 of an update: every voxel of this update's jobs becomes BUILDING, every voxel of a deferred job
// UNBUILT (job voxels numbered from buildVoxelCount on). The brick it held (if any) goes back to the free
// list exactly once (atomic exchange), and its reference count is reset. So does the base brick kept
// under a dynamic instance's composite (prepare_overlay.comp): a full job builds the static field anew.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint jobCount; uint voxelCount; uint buildVoxelCount; } params;
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
    uint old = atomicExchange(brickMaps[key], index < params.buildVoxelCount ? BL_SDF_BUILDING : BL_SDF_UNBUILT);
    voxelRefs[2u * key] = 0u;
    uint oldBase = atomicExchange(baseMaps[key], BL_SDF_NO_BASE);
    for (int i = 0; i < 2; ++i) {
        uint brick = i == 0 ? old : oldBase;
        if (brick >= BL_SDF_FIRST_STATE) continue;
        uint slot = atomicAdd(counters[C_FREE_COUNT], 1u);
        freeStack[slot] = brick;
        atomicAdd(counters[C_BRICKS_FREED], 1u);
    }
}
