#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"
#include "bricklight/rgb9e5.glsl"
// Fills voxels of level L that lie inside level L − 1 from their 2³ children there (the voxelization leaves
// them to this pass). Values mean what a cone sees through a voxel's cross-section:
//  * opacity along each axis: the two children of each column along it combine as complements
//    (1 − (1 − a)(1 − b)) of their opacity along that axis, the four columns average;
//  * emittance towards direction d: in each of the four columns along d's axis, the child nearer the viewer
//    (further along d) plus the other one seen through it (× (1 − its opacity along the axis)); the four
//    columns' sum is divided by 4, since a parent's face is four children's faces. Isotropic emittance takes the
//    mean of that over the six directions.
// Every loop has constant bounds and every array a constant index once unrolled, so all of it stays in
// registers.
// Rows of 32 along x: neighbouring threads touch neighbouring texels.
layout(local_size_x = 32, local_size_y = 2, local_size_z = 1) in;
BL_CONSTANTS(0) uniform Box {
    ivec4 minLevel;  // xyz: the box's lowest world voxel of level L, w: L (≥ 1)
    ivec4 size;      // xyz: the box's extent in voxels
    uvec4 params;    // x: the resolution, y: emittance directions (0, 1 or 6)
} box;
BL_IMAGE(0, r32ui) uniform coherent uimage3D atlas;

vec3 loadRadiance(uint region, uint level, ivec3 voxel, uint resolution) {
    return blDecodeRgb9e5(imageLoad(atlas, vctTexel(region, level, voxel, resolution)).x);
}

void main() {
    ivec3 local = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(local, box.size.xyz))) return;
    uint level = uint(box.minLevel.w), resolution = box.params.x, directions = box.params.y;
    ivec3 voxel = box.minLevel.xyz + local;
    // Children in x-fastest order: child i is at 2·voxel + (i & 1, (i >> 1) & 1, i >> 2).
    vec3 alpha[8];
    ivec3 child[8];
    uint words[8];
    bool empty = true;
    for (int i = 0; i < 8; ++i) {
        child[i] = voxel * 2 + ivec3(i & 1, (i >> 1) & 1, i >> 2);
        words[i] = imageLoad(atlas, vctTexel(0u, level - 1u, child[i], resolution)).x;
        empty = empty && words[i] == 0u;
        alpha[i] = vctUnpackOpacity(words[i]);
    }
    imageStore(atlas, vctTexel(0u, level, voxel, resolution), uvec4(vctDownsampleOpacity(words)));
    // The mode's conditions carry per-invocation data (always true here): lavapipe compiles a variant per dispatch
    // for a branch on constants alone (docs/notes/soak.md), and every box is a dispatch.
    bool inBox = local.x < box.size.x;
    if (directions == 0u && inBox) return;

    bool isotropic = directions == 1u && inBox;
    bool anisotropic = directions == 6u && inBox;
    if (empty) {  // no surface among the children, so no light: zeros without reading their light (most voxels)
        for (uint d = 0u; d < directions; ++d) imageStore(atlas, vctTexel(1u + d, level, voxel, resolution), uvec4(0u));
        return;
    }
    precise vec3 mean = vec3(0.0);
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            int d = axis + 3 * side;  // +axis for side 0, −axis for side 1
            uint region = isotropic ? 1u : 1u + uint(d);
            precise vec3 sum = vec3(0.0);
            for (int j = 0; j < 4; ++j) {
                int lower = axis == 0 ? 2 * j : (axis == 1 ? (j & 1) + 4 * (j >> 1) : j);
                int upper = lower + (1 << axis);
                // Light towards +axis leaves through the upper child first; towards −axis, the lower.
                int nearChild = side == 0 ? upper : lower, farChild = side == 0 ? lower : upper;
                vec3 nearE = loadRadiance(region, level - 1u, child[nearChild], resolution);
                vec3 farE = loadRadiance(region, level - 1u, child[farChild], resolution);
                sum += nearE + (1.0 - alpha[nearChild][axis]) * farE;
            }
            sum *= 0.25;
            mean += sum * (1.0 / 6.0);
            if (anisotropic) imageStore(atlas, vctTexel(region, level, voxel, resolution), uvec4(blPackRgb9e5(sum)));
        }
    if (isotropic) imageStore(atlas, vctTexel(1u, level, voxel, resolution), uvec4(blPackRgb9e5(mean)));
}
