#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Depth pyramid: mip 0 from the depth texture and mips 1..5 (depth_pyramid_tiles_body.glsl).
#define DEPTH_PYRAMID_FIRST
#include "depth_pyramid_tiles_body.glsl"
