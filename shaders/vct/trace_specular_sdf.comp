#version 450
#extension GL_GOOGLE_include_directive : require
// Cones that stop where a ray through the distance field meets a surface (vct::TraceDesc::occlusionField).
#define VCT_SDF_OCCLUSION
#include "trace_specular_body.glsl"
