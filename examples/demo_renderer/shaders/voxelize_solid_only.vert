#version 450
#extension GL_GOOGLE_include_directive : require
// Voxelization (render/voxelize.vert) without the alpha-tested materials' triangles (RasterOptions::foliage
// LeftOut, the naive variant kept for comparison): they get a NaN position, which the voxelization's
// per-triangle setup drops (bricklight/voxelize.glsl), as render/alpha_pass.vert drops the others. The cards are
// still drawn into the G-buffer and lit; they neither block nor send indirect light.
#include "bricklight/bindings.glsl"
#include "bricklight/voxelize_vertex.glsl"
BL_READ_BUFFER(2) Materials { vec4 materials[]; };  // 4 per material; [4m + 3].x: the alpha cut-off (0: opaque)
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in uint material;
layout(location = 4) in vec2 uv;
BL_VOXEL_VERTEX_OUTPUTS

void main() {
    bool alphaTested = materials[4u * material + 3u].x > 0.0;
    blVoxelVertex(alphaTested ? vec3(uintBitsToFloat(0x7FC00000u)) : position, normal, vec4(float(material), uv, 0.0), vec4(0.0));
}
