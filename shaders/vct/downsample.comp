#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"
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
// Rows of 32 along x: neighbouring threads touch neighbouring texels and emittance words (coalesced).
layout(local_size_x = 32, local_size_y = 2, local_size_z = 1) in;
BL_CONSTANTS(0) uniform Box {
    ivec4 minLevel;  // xyz: the box's lowest world voxel of level L, w: L (≥ 1)
    ivec4 size;      // xyz: the box's extent in voxels
    uvec4 params;    // x: the resolution, y: emittance words per voxel (0, 3 or 18), z: the levels
} box;
BL_IMAGE(0, r32ui) uniform coherent uimage3D opacityVolume;
BL_STORAGE_BUFFER(0) Emittance { uint words[]; } emittance;

void main() {
    ivec3 local = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(local, box.size.xyz))) return;
    uint level = uint(box.minLevel.w), resolution = box.params.x, channels = box.params.y;
    ivec3 voxel = box.minLevel.xyz + local;
    // Children in x-fastest order: child i is at 2·voxel + (i & 1, (i >> 1) & 1, i >> 2).
    vec3 alpha[8];
    uint base[8];
    bool empty = true;
    for (int i = 0; i < 8; ++i) {
        ivec3 child = voxel * 2 + ivec3(i & 1, (i >> 1) & 1, i >> 2);
        uint word = imageLoad(opacityVolume, vctTexel(level - 1u, child, resolution)).x;
        empty = empty && word == 0u;
        alpha[i] = vctUnpackOpacity(word);
        base[i] = vctTexelIndex(level - 1u, child, resolution);
    }
    precise vec3 opacity = vec3(0.0);  // precise: Vulkan and GL round alike
    for (int axis = 0; axis < 3; ++axis)
        for (int j = 0; j < 4; ++j) {
            // The j-th column along `axis`: its lower child has the axis bit clear.
            int lower = axis == 0 ? 2 * j : (axis == 1 ? (j & 1) + 4 * (j >> 1) : j);
            int upper = lower + (1 << axis);
            opacity[axis] += (1.0 - (1.0 - alpha[lower][axis]) * (1.0 - alpha[upper][axis])) * 0.25;
        }
    imageStore(opacityVolume, vctTexel(level, voxel, resolution), uvec4(vctPackOpacity(opacity)));
    // The mode's conditions carry per-invocation data (always true here): lavapipe compiles a variant per dispatch
    // for a branch on constants alone (docs/notes/soak.md), and every box is a dispatch.
    bool inBox = local.x < box.size.x;
    if (channels == 0u && inBox) return;

    bool isotropic = channels == 3u && inBox;
    bool anisotropic = channels == 18u && inBox;
    uint parent = vctTexelIndex(level, voxel, resolution);
    uint texelCount = resolution * resolution * resolution * box.params.z;
    if (empty) {  // no surface among the children, so no light: zeros without reading their words (most voxels)
        for (uint w = 0u; w < channels; ++w) emittance.words[vctWordIndex(parent, w, texelCount)] = 0u;
        return;
    }
    precise vec3 mean = vec3(0.0);
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            int d = axis + 3 * side;  // +axis for side 0, −axis for side 1
            uint word = isotropic ? 0u : uint(d) * 3u;
            precise vec3 sum = vec3(0.0);
            for (int j = 0; j < 4; ++j) {
                int lower = axis == 0 ? 2 * j : (axis == 1 ? (j & 1) + 4 * (j >> 1) : j);
                int upper = lower + (1 << axis);
                // Light towards +axis leaves through the upper child first; towards −axis, the lower.
                int nearChild = side == 0 ? upper : lower, farChild = side == 0 ? lower : upper;
                vec3 nearE = vec3(emittance.words[vctWordIndex(base[nearChild], word, texelCount)],
                                  emittance.words[vctWordIndex(base[nearChild], word + 1u, texelCount)],
                                  emittance.words[vctWordIndex(base[nearChild], word + 2u, texelCount)]);
                vec3 farE = vec3(emittance.words[vctWordIndex(base[farChild], word, texelCount)],
                                 emittance.words[vctWordIndex(base[farChild], word + 1u, texelCount)],
                                 emittance.words[vctWordIndex(base[farChild], word + 2u, texelCount)]);
                sum += nearE + (1.0 - alpha[nearChild][axis]) * farE;
            }
            sum *= 0.25;
            mean += sum / 6.0;
            if (anisotropic) {
                uvec3 units = uvec3(min(sum + 0.5, vec3(4.0e9)));
                emittance.words[vctWordIndex(parent, uint(d) * 3u, texelCount)] = units.x;
                emittance.words[vctWordIndex(parent, uint(d) * 3u + 1u, texelCount)] = units.y;
                emittance.words[vctWordIndex(parent, uint(d) * 3u + 2u, texelCount)] = units.z;
            }
        }
    if (isotropic) {
        uvec3 units = uvec3(min(mean + 0.5, vec3(4.0e9)));
        emittance.words[vctWordIndex(parent, 0u, texelCount)] = units.x;
        emittance.words[vctWordIndex(parent, 1u, texelCount)] = units.y;
        emittance.words[vctWordIndex(parent, 2u, texelCount)] = units.z;
    }
}
