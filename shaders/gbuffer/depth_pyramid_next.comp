#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Depth pyramid: mips s + 1 .. s + 5 from mip s (depth_pyramid_tiles_body.glsl).
#include "depth_pyramid_tiles_body.glsl"
