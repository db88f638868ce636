#version 450
#extension GL_GOOGLE_include_directive : require
#include "trace_diffuse_body.glsl"
