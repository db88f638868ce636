#version 450
#extension GL_GOOGLE_include_directive : require
// voxelize_coverage.frag's hooks for vct::VoxelScene's compute voxelizer.
#define BL_VOXEL_COVERAGE
#include "bricklight/voxelize_compute.glsl"
#include "coverage_hook.glsl"
