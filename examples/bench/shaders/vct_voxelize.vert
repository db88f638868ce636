#version 450
#extension GL_GOOGLE_include_directive : require
// The benchmark's voxelization vertex shader: world-space positions and normals.
#include "bricklight/voxelize_vertex.glsl"
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
BL_VOXEL_VERTEX_OUTPUTS

void main() { blVoxelVertex(position, normal, vec4(0.0), vec4(0.0)); }
