// Builds one mip of the coarsest level in the atlas (vct_layout.glsl) from the level or the mip below it (included by
// mip_build_opacity.comp, mip_build_isotropic.comp and mip_build_anisotropic.comp, which define
// BL_VCT_DIRECTIONS 0, 1 or 6). The combination is downsample.comp's, on the traced (float) values:
//  * opacity along each axis: each column of two children along it combines as complements, the four columns
//    average;
//  * emittance towards a direction: per column along its axis, the child nearer the viewer plus the other seen
//    through it, the four columns' sum / 4; isotropic: the mean of that over the six directions.
// Children outside the source's region count as empty, so a mip voxel that reaches past the coarsest level holds
// only the part inside it. Every texel of the mip's box is written, its empty border too.
#include "bricklight/rgb9e5.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
BL_CONSTANTS(0) uniform Mip {
    ivec4 target;     // xyz: the mip's box within a region (x from the region's first column past the border), w: its size per axis
    ivec4 targetMin;  // xyz: the world voxel (of this mip) of the box's first texel
    ivec4 source;     // xyz: the source's box within a region, w: its width per axis
    ivec4 sourceMin;  // xyz: the source's first valid world voxel
    ivec4 shift;      // xyz: where that voxel is stored, toroidally (the level: its coordinates modulo the width; a mip: 0); w: the resolution
} mip;
BL_IMAGE(0, r32ui) uniform uimage3D atlas;

ivec3 atlasTexel(uint region, ivec3 inRegion) { return inRegion + ivec3(vctRegionX(region, uint(mip.shift.w)) + 1, 0, 0); }

vec3 loadEmittance(ivec3 t, uint d, bool valid) {
    if (!valid) return vec3(0.0);
    return blDecodeRgb9e5(imageLoad(atlas, atlasTexel(1u + d, t)).x);
}

void storeEmittance(ivec3 t, uint d, vec3 e) { imageStore(atlas, atlasTexel(1u + d, t), uvec4(blPackRgb9e5(e), 0u, 0u, 0u)); }

void main() {
    ivec3 local = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(local, ivec3(mip.target.w)))) return;
    ivec3 voxel = mip.targetMin.xyz + local;
    int width = mip.source.w;
    // Children in x-fastest order: child i is at 2·voxel + (i & 1, (i >> 1) & 1, i >> 2).
    ivec3 texel[8];
    bool valid[8];
    vec3 alpha[8];
    uint words[8];
    bool empty = true;
    for (int i = 0; i < 8; ++i) {
        ivec3 rel = voxel * 2 + ivec3(i & 1, (i >> 1) & 1, i >> 2) - mip.sourceMin.xyz;
        valid[i] = all(greaterThanEqual(rel, ivec3(0))) && all(lessThan(rel, ivec3(width)));
        // Toroidal for the level (shift < width, so one subtraction wraps), plain for a mip (shift 0).
        ivec3 wrapped = clamp(rel, ivec3(0), ivec3(width - 1)) + mip.shift.xyz;
        wrapped -= mix(ivec3(0), ivec3(width), greaterThanEqual(wrapped, ivec3(width)));
        texel[i] = mip.source.xyz + wrapped;
        words[i] = valid[i] ? imageLoad(atlas, atlasTexel(0u, texel[i])).x : 0u;
        alpha[i] = vctUnpackOpacity(words[i]);
        empty = empty && words[i] == 0u;
    }
    ivec3 t = mip.target.xyz + local;
    imageStore(atlas, atlasTexel(0u, t), uvec4(vctDownsampleOpacity(words)));
#if BL_VCT_DIRECTIONS >= 1
    vec3 mean = vec3(0.0);
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            uint d = uint(axis + 3 * side);  // +axis for side 0, −axis for side 1
            vec3 sum = vec3(0.0);
            for (int j = 0; j < 4 && !empty; ++j) {
                int lower = axis == 0 ? 2 * j : (axis == 1 ? (j & 1) + 4 * (j >> 1) : j);
                int upper = lower + (1 << axis);
                // Light towards +axis leaves through the upper child first; towards −axis, the lower.
                int nearChild = side == 0 ? upper : lower, farChild = side == 0 ? lower : upper;
                uint stored = BL_VCT_DIRECTIONS == 6 ? d : 0u;
                sum += loadEmittance(texel[nearChild], stored, valid[nearChild]) +
                       (1.0 - alpha[nearChild][axis]) * loadEmittance(texel[farChild], stored, valid[farChild]);
            }
            sum *= 0.25;
            mean += sum / 6.0;
#if BL_VCT_DIRECTIONS == 6
            storeEmittance(t, d, sum);
#endif
        }
#if BL_VCT_DIRECTIONS == 1
    storeEmittance(t, 0u, mean);
#endif
#endif
}
