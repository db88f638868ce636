#version 450
#extension GL_GOOGLE_include_directive : require
// The renderer's emittance (voxel_emittance_body.glsl) with alpha-tested materials weighed by their coverage
// (voxel_alpha.glsl): RasterOptions::foliage AlphaAware.
#define BL_VOXEL_COVERAGE
#include "voxel_emittance_body.glsl"
