#version 450
#extension GL_GOOGLE_include_directive : require
// An application's voxelization vertex shader as tests write it: positions and normals already in world space;
// user0 is the position (the coverage tests read it as texture coordinates).
#include "bricklight/voxelize_vertex.glsl"
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
BL_VOXEL_VERTEX_OUTPUTS

void main() { blVoxelVertex(position, normal, vec4(position, 1.0), vec4(0.0)); }
