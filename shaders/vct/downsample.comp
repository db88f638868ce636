#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"
// Fills voxels of level L that lie inside level L − 1 from their 2³ children there (the voxelization leaves
// them to this pass). Values mean what a cone sees through a voxel's cross-section:
//  * opacity along each axis: the two children of each column along it combine as complements
//    (1 − (1 − a)(1 − b)) of their opacity along that axis, the four columns average;
//  * emittance towards direction d: in each of the four columns along d's axis, the child nearer the viewer
//    (further along d) plus the other one seen through it (× (1 − its opacity)); the four columns' sum is
//    divided by 4, since a parent's face is four children's faces. Isotropic emittance takes the mean of that
//    over the six directions.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
BL_CONSTANTS(0) uniform Box {
    ivec4 minLevel;  // xyz: the box's lowest world voxel of level L, w: L (≥ 1)
    ivec4 size;      // xyz: the box's extent in voxels
    uvec4 params;    // x: the resolution, y: emittance words per voxel (0, 3 or 18)
} box;
BL_IMAGE(0, r32ui) uniform coherent uimage3D opacityVolume;
BL_STORAGE_BUFFER(0) Emittance { uint words[]; } emittance;

const uint MAX_WORDS = 18u;

void main() {
    ivec3 local = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(local, box.size.xyz))) return;
    uint level = uint(box.minLevel.w), resolution = box.params.x, channels = box.params.y;
    ivec3 voxel = box.minLevel.xyz + local;
    // Children in x-fastest order: child i is at 2·voxel + (i & 1, (i >> 1) & 1, i >> 2).
    vec3 alpha[8];
    uint base[8];
    for (int i = 0; i < 8; ++i) {
        ivec3 child = voxel * 2 + ivec3(i & 1, (i >> 1) & 1, i >> 2);
        alpha[i] = vctUnpackOpacity(imageLoad(opacityVolume, vctTexel(level - 1u, child, resolution)).x);
        base[i] = vctTexelIndex(level - 1u, child, resolution) * channels;
    }
    precise vec3 opacity = vec3(0.0);  // precise: Vulkan and GL round alike
    for (int axis = 0; axis < 3; ++axis) {
        int step = 1 << axis;
        for (int i = 0; i < 8; ++i)
            if ((i & step) == 0) opacity[axis] += (1.0 - (1.0 - alpha[i][axis]) * (1.0 - alpha[i + step][axis])) * 0.25;
    }
    imageStore(opacityVolume, vctTexel(level, voxel, resolution), uvec4(vctPackOpacity(opacity)));

    uint directions = channels / 3u;
    uint parent = vctTexelIndex(level, voxel, resolution) * channels;
    for (uint d = 0u; d < directions; ++d) {
        precise vec3 sum = vec3(0.0);
        // The directions this output stands for: d itself, or all six for the isotropic volume.
        uint first = directions == 1u ? 0u : d, last = directions == 1u ? 6u : d + 1u;
        for (uint dir = first; dir < last; ++dir) {
            int step = 1 << (dir % 3u);
            bool positive = dir < 3u;
            uint word = directions == 1u ? 0u : d * 3u;
            for (int i = 0; i < 8; ++i) {
                if ((i & step) != 0) continue;
                int nearChild = positive ? i + step : i, farChild = positive ? i : i + step;
                for (uint c = 0u; c < 3u; ++c) {
                    float nearE = float(emittance.words[base[nearChild] + word + c]);
                    float farE = float(emittance.words[base[farChild] + word + c]);
                    sum[c] += nearE + (1.0 - alpha[nearChild][dir % 3u]) * farE;
                }
            }
        }
        sum /= 4.0 * float(last - first);
        for (uint c = 0u; c < 3u; ++c) emittance.words[parent + d * 3u + c] = uint(min(sum[c] + 0.5, 4.0e9));
    }
}
