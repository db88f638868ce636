// Turns one box of one level's accumulation words into the volumes cones sample (included by
// resolve_opacity.comp, resolve_isotropic.comp and resolve_anisotropic.comp, which define BL_VCT_DIRECTIONS 0,
// 1 or 6): opacity as a float, emittance as radiance (RGB9E5 bits through R32_UINT; cones sample RGB9E5_FLOAT
// views), in the traced layout — levels stacked in z with one border slice on each side holding the level's
// opposite (toroidally adjacent) slice, so that hardware filtering wraps in z as the sampler's repeat mode does
// in x and y.
#include "bricklight/rgb9e5.glsl"
// Rows of 32 along x: neighbouring threads touch neighbouring texels and emittance words (coalesced).
layout(local_size_x = 32, local_size_y = 2, local_size_z = 1) in;
BL_CONSTANTS(0) uniform Box {
    ivec4 minLevel;  // xyz: the box's lowest world voxel, w: the level
    ivec4 size;      // xyz: the box's extent in voxels
    uvec4 params;    // x: the resolution, y: words per voxel (3 × BL_VCT_DIRECTIONS), z: the levels
    vec4 scales;     // x: radiance per fixed-point unit
} box;
BL_IMAGE(0, r32ui) uniform readonly uimage3D opacityWords;
BL_READ_BUFFER(0) Emittance { uint words[]; } emittance;
BL_IMAGE(1, rgba8) uniform writeonly image3D tracedOpacity;  // rgb: along x, y, z
#if BL_VCT_DIRECTIONS >= 1
BL_IMAGE(2, r32ui) uniform writeonly uimage3D tracedEmittance0;
#endif
#if BL_VCT_DIRECTIONS == 6
BL_IMAGE(3, r32ui) uniform writeonly uimage3D tracedEmittance1;
BL_IMAGE(4, r32ui) uniform writeonly uimage3D tracedEmittance2;
BL_IMAGE(5, r32ui) uniform writeonly uimage3D tracedEmittance3;
BL_IMAGE(6, r32ui) uniform writeonly uimage3D tracedEmittance4;
BL_IMAGE(7, r32ui) uniform writeonly uimage3D tracedEmittance5;
#endif

// The radiance one direction's words hold, packed as RGB9E5_FLOAT.
uvec4 radianceOf(uint texel, uint direction) {
    if (texel == ~0u) return uvec4(0u);  // an empty voxel
    uint texelCount = box.params.x * box.params.x * box.params.x * box.params.z;
    uint w = direction * 3u;
    vec3 radiance = vec3(float(emittance.words[vctWordIndex(texel, w, texelCount)]), float(emittance.words[vctWordIndex(texel, w + 1u, texelCount)]),
                         float(emittance.words[vctWordIndex(texel, w + 2u, texelCount)])) * box.scales.x;
    return uvec4(blPackRgb9e5(radiance), 0u, 0u, 0u);
}

void store(ivec3 t, vec3 opacity, uint base) {
    imageStore(tracedOpacity, t, vec4(opacity, 0.0));
#if BL_VCT_DIRECTIONS >= 1
    imageStore(tracedEmittance0, t, radianceOf(base, 0u));
#endif
#if BL_VCT_DIRECTIONS == 6
    imageStore(tracedEmittance1, t, radianceOf(base, 1u));
    imageStore(tracedEmittance2, t, radianceOf(base, 2u));
    imageStore(tracedEmittance3, t, radianceOf(base, 3u));
    imageStore(tracedEmittance4, t, radianceOf(base, 4u));
    imageStore(tracedEmittance5, t, radianceOf(base, 5u));
#endif
}

void main() {
    ivec3 local = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(local, box.size.xyz))) return;
    uint level = uint(box.minLevel.w), resolution = box.params.x;
    ivec3 voxel = box.minLevel.xyz + local;
    ivec3 texel = vctTexel(level, voxel, resolution);
    uint opacityWord = imageLoad(opacityWords, texel).x;
    vec3 opacity = vctUnpackOpacity(opacityWord);
    // An empty voxel holds no light either (the voxelization writes light only into voxels it makes opaque), so
    // its words are not read: most voxels are empty, and those reads were most of this pass's traffic.
    uint base = opacityWord == 0u ? ~0u : vctTexelIndex(level, voxel, resolution);
    int r = int(resolution);
    ivec3 t = vctTexel(0u, voxel, resolution);  // within the level
    int slab = int(level) * (r + 2) + 1;
    store(ivec3(t.xy, slab + t.z), opacity, base);
    // The border slices: the level's first slice again after its last, and its last before its first.
    if (t.z == 0) store(ivec3(t.xy, slab + r), opacity, base);
    if (t.z == r - 1) store(ivec3(t.xy, slab - 1), opacity, base);
}
