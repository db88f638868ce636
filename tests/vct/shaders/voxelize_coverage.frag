#version 450
#extension GL_GOOGLE_include_directive : require
// An alpha-tested material's voxelization as an application writes it: emissive (constants 0) with a coverage
// hook (coverage_hook.glsl).
#define BL_VOXEL_COVERAGE
#include "bricklight/voxelize.glsl"
#include "coverage_hook.glsl"
