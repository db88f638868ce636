#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
// One thread per job voxel, after allocation: a voxel still BUILDING was touched by no triangle: EMPTY.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint jobCount; uint voxelCount; } params;
BL_READ_BUFFER(0) JobTable { BL_SDF_JOB_TABLE_BODY } jobTable;
BL_STORAGE_BUFFER(0) BrickMaps { uint brickMaps[]; };
BL_STORAGE_BUFFER(1) Counters { uint counters[]; };
#include "job_lookup.glsl"

shared uint groupBuilt;

void main() {
    if (gl_LocalInvocationIndex == 0u) groupBuilt = 0u;
    barrier();
    uint index = gl_GlobalInvocationID.y * (BL_SDF_WIDE_GROUPS * 64u) + gl_GlobalInvocationID.x;
    if (index < params.voxelCount) {
        ivec3 voxel;
        uint cascade;
        blSdfJobVoxel(index, params.jobCount, voxel, cascade);
        uint key = cascade * BL_SDF_CASCADE_VOXELS + blSdfPhysicalIndex(voxel);
        if (atomicCompSwap(brickMaps[key], BL_SDF_BUILDING, BL_SDF_EMPTY) == BL_SDF_BUILDING) atomicAdd(groupBuilt, 1u);
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && groupBuilt > 0u) atomicAdd(counters[C_VOXELS_BUILT], groupBuilt);
}
