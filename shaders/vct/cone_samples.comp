#version 450
#extension GL_GOOGLE_include_directive : require
#include "cone_samples_body.glsl"
