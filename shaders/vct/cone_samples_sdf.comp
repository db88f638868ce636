#version 450
#extension GL_GOOGLE_include_directive : require
#define VCT_SDF_OCCLUSION
#include "cone_samples_body.glsl"
