#version 450
#extension GL_GOOGLE_include_directive : require
// Voxelization without emittance (voxel AO, or materials that send no light): opacity only.
#define BL_VOXEL_OPACITY_ONLY
#include "bricklight/voxelize.glsl"
