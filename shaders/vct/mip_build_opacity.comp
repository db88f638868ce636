#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"
#define BL_VCT_DIRECTIONS 0
#include "mip_build_body.glsl"
