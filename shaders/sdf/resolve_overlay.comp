#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
// Last pass of an update's overlay round, one thread per overlay job voxel: a voxel still BUILDING was
// reached by no dynamic triangle: its static field (the base) is the live one again, and it has no base.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint jobCount; uint voxelCount; } params;
BL_READ_BUFFER(0) JobTable { BL_SDF_JOB_TABLE_BODY } jobTable;
BL_STORAGE_BUFFER(0) BrickMaps { uint brickMaps[]; };
BL_STORAGE_BUFFER(1) BaseMaps { uint baseMaps[]; };
#include "job_lookup.glsl"

void main() {
    uint index = gl_GlobalInvocationID.y * (BL_SDF_WIDE_GROUPS * 64u) + gl_GlobalInvocationID.x;
    if (index >= params.voxelCount) return;
    ivec3 voxel;
    uint cascade;
    blSdfJobVoxel(index, params.jobCount, voxel, cascade);
    uint key = cascade * BL_SDF_CASCADE_VOXELS + blSdfPhysicalIndex(voxel);
    if (brickMaps[key] != BL_SDF_BUILDING) return;  // built from dynamic triangles, or left unbuilt
    uint base = baseMaps[key];
    if (base == BL_SDF_NO_BASE) return;  // another thread of an overlapping job restored it
    brickMaps[key] = base;
    baseMaps[key] = BL_SDF_NO_BASE;
}
