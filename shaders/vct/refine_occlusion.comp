#version 450
#extension GL_GOOGLE_include_directive : require
// Voxel AO (a clip-map without emittance): the refined pixels with the cones' light compiled out
// (BL_CONE_TRACE_OCCLUSION_ONLY) and a history of the ambient alone (history_blend.glsl).
#define BL_CONE_TRACE_OCCLUSION_ONLY
#include "refine_diffuse_body.glsl"
