#version 450
#extension GL_GOOGLE_include_directive : require
// The compute voxelizer of vct::VoxelScene's registered meshes (bricklight/voxelize_compute.glsl) for
// materials without a computeShader of their own: opacity only.
#define BL_VOXEL_OPACITY_ONLY
#include "bricklight/voxelize_compute.glsl"
