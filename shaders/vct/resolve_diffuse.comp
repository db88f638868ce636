#version 450
#extension GL_GOOGLE_include_directive : require
#include "resolve_diffuse_body.glsl"
