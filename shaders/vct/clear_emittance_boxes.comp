#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"
// Clears the emittance accumulation words of one box of world voxels of one level (the buffer twin of
// clear_boxes.comp). x runs over the box's voxels × the words per voxel, so no loop depends on constants alone.
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
BL_CONSTANTS(0) uniform Box {
    ivec4 minLevel;  // xyz: the box's lowest world voxel, w: the level
    ivec4 size;      // xyz: the box's extent in voxels
    uvec4 params;    // x: the resolution, y: words per voxel, z: the levels
} box;
BL_STORAGE_BUFFER(0) Emittance { uint words[]; } emittance;

void main() {
    uint channels = box.params.y;
    uint flat_ = gl_GlobalInvocationID.x;
    uint voxelX = flat_ / channels, word = flat_ % channels;
    ivec3 local = ivec3(int(voxelX), int(gl_GlobalInvocationID.y), int(gl_GlobalInvocationID.z));
    if (any(greaterThanEqual(local, box.size.xyz))) return;
    uint texelCount = box.params.x * box.params.x * box.params.x * box.params.z;
    emittance.words[vctWordIndex(vctTexelIndex(uint(box.minLevel.w), box.minLevel.xyz + local, box.params.x), word, texelCount)] = 0u;
}
