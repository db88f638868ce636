#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#define SUN_VISIBILITY_FROM_MASK
#include "shadow_sun_light_body.glsl"
