#version 450
#extension GL_GOOGLE_include_directive : require
// Voxel AO (a clip-map without emittance, vct::EmittanceMode::None): the diffuse cones of trace_diffuse.comp with
// the light's arithmetic compiled out (BL_CONE_TRACE_OCCLUSION_ONLY), since such a clip-map holds none.
#define BL_CONE_TRACE_OCCLUSION_ONLY
#include "trace_diffuse_body.glsl"
