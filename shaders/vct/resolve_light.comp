#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"
#include "bricklight/rgb9e5.glsl"
// Turns the light one box of one level gathered into radiance: each direction's atlas word holds the tagged index of
// the pool entry the voxelization summed the voxel's fixed-point light in (bricklight/voxelize.glsl), or still the
// previous update's radiance (no light this time: 0); the word becomes the light a cone sees through the voxel's
// face as RGB9E5 bits (below), and the entry is zeroed for the next update.
// Rows of 32 along x: neighbouring threads touch neighbouring texels.
layout(local_size_x = 32, local_size_y = 2, local_size_z = 1) in;
BL_CONSTANTS(0) uniform Box {
    ivec4 minLevel;  // xyz: the box's lowest world voxel, w: the level
    ivec4 size;      // xyz: the box's extent in voxels
    uvec4 params;    // x: the resolution, y: emittance directions (1 or 6)
    vec4 scales;     // x: radiance per fixed-point unit
} box;
BL_IMAGE(0, r32ui) uniform uimage3D atlas;
BL_STORAGE_BUFFER(0) Light { uint words[]; } light;

void main() {
    ivec3 local = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(local, box.size.xyz))) return;
    uint level = uint(box.minLevel.w), resolution = box.params.x;
    ivec3 voxel = box.minLevel.xyz + local;
    vec3 opacity = vctUnpackOpacity(imageLoad(atlas, vctTexel(0u, level, voxel, resolution)).x);  // along x, y, z
    for (uint d = 0u; d < box.params.y; ++d) {
        ivec3 texel = vctTexel(1u + d, level, voxel, resolution);
        uint word = imageLoad(atlas, texel).x;
        if (!vctIsLightEntry(word)) {
            if (word != 0u) imageStore(atlas, texel, uvec4(0u));  // no light this update
            continue;
        }
        uint entry = 4u * vctLightEntryOf(word);
        vec3 radiance = vec3(float(light.words[entry]), float(light.words[entry + 1u]), float(light.words[entry + 2u])) * box.scales.x;
        // What a cone sees through the voxel's face: the radiance of the surfaces that send light this way (their
        // coverage-weighted mean: where they cover more than the face they hide one another, and a sum would count
        // the hidden ones too — two parallel walls, both sides of a box thinner than the voxel — and light fed back
        // through bounces would grow) times the share of the face they block, the voxel's opacity along the axis,
        // so that the light per unit of opacity a cone takes is the surfaces' radiance wherever they lie in the
        // voxel. (The light premultiplied by its own coverage instead made a tilted wall's voxels send less than
        // their opacity takes: their coverage is the surface's area in the voxel, their opacity the whole normal
        // component.)
        // (A division, which the GLSL and SPIR-V compilers of one driver may round differently: Mesa's agree, bit
        // for bit, as the cross-backend tests check.)
        precise float coverage = float(light.words[entry + 3u]) / VCT_COVERAGE_UNITS;
        if (box.params.y == 1u) {
            radiance /= max(coverage, 1.0);  // isotropic: one value for every direction, premultiplied by coverage
        } else if (coverage > 0.0) {
            precise float blocked = opacity[d % 3u] / coverage;
            radiance *= blocked;
        } else {
            radiance = vec3(0.0);
        }
        light.words[entry] = 0u;
        light.words[entry + 1u] = 0u;
        light.words[entry + 2u] = 0u;
        light.words[entry + 3u] = 0u;
        imageStore(atlas, texel, uvec4(blPackRgb9e5(radiance)));
    }
}
