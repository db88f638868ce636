#version 450
#extension GL_GOOGLE_include_directive : require
// Voxelization (vct::Clipmap::voxelizationState) of GpuScene's vertex buffer: world-space triangles as they are;
// the material (as a float, exact below 2^24 and rounded back) and the texture coordinates reach the emittance.
#include "bricklight/voxelize_vertex.glsl"
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in uint material;
layout(location = 4) in vec2 uv;
BL_VOXEL_VERTEX_OUTPUTS

void main() { blVoxelVertex(position, normal, vec4(float(material), uv, 0.0), vec4(0.0)); }
