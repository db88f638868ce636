#version 450
#extension GL_GOOGLE_include_directive : require
// The renderer's emittance (voxel_emittance_body.glsl) without the coverage hook: alpha-tested cards are
// voxelized as solid surfaces, their cut-out texels too (RasterOptions::foliage Opaque, the naive variant kept
// for comparison).
#include "voxel_emittance_body.glsl"
