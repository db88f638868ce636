#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"
// Clears one box of world voxels of one level (what this update rewrites) in the atlas's opacity region, in place in
// the toroidal layout. The direction regions need no clear (vct_layout.glsl's vctTagLightEntry); the border columns
// and slices follow in borders.comp.
// Rows of 32 along x: neighbouring threads touch neighbouring texels.
layout(local_size_x = 32, local_size_y = 2, local_size_z = 1) in;
BL_CONSTANTS(0) uniform Box {
    ivec4 minLevel;  // xyz: the box's lowest world voxel, w: the level
    ivec4 size;      // xyz: the box's extent in voxels
    uvec4 params;    // x: the resolution, y: the value written
} box;
BL_IMAGE(0, r32ui) uniform writeonly uimage3D atlas;

void main() {
    ivec3 local = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(local, box.size.xyz))) return;
    imageStore(atlas, vctTexel(0u, uint(box.minLevel.w), box.minLevel.xyz + local, box.params.x), uvec4(box.params.y));
}
