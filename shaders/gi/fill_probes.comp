#version 450
#extension GL_GOOGLE_include_directive : require
#include "fill_probes_body.glsl"
