#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"
#define BL_VCT_DIRECTIONS 6
#include "mip_build_body.glsl"
