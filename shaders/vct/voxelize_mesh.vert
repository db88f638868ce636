#version 450
#extension GL_GOOGLE_include_directive : require
#include "voxelize_mesh_body.glsl"
