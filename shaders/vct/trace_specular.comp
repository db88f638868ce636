#version 450
#extension GL_GOOGLE_include_directive : require
#include "trace_specular_body.glsl"
