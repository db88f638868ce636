#version 450
#extension GL_GOOGLE_include_directive : require
#define VCT_MESH_FLAT
#include "voxelize_mesh_body.glsl"
