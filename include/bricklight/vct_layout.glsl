// The voxel clip-map's layout on the device (include/bricklight/vct.h), shared by our voxelization, clear,
// downsampling and tracing passes and by the application's voxelization fragment shader (bricklight/voxelize.glsl).
//
// Everything lives in one R32_UINT 3D texture, the atlas: regions side by side in x, each resolution + 2 texels
// wide — region 0 the opacity (sampled through an RGBA8_UNORM view), regions 1.. the radiance of each emittance
// direction (RGB9E5 bits, sampled through an RGB9E5_FLOAT view; one region when isotropic). Within a region,
// level L takes z slices [L × (resolution + 2), (L + 1) × (resolution + 2)) and x columns [0, resolution + 2):
// the level's voxels toroidally (a world voxel at its coordinates modulo the resolution, so that a level keeps
// what it still covers while it scrolls) with a border slice and a border column on each side holding the
// opposite (toroidally adjacent) slice or column, so that hardware filtering wraps as the sampler's repeat mode
// does in y. Above the levels one slab of resolution / 2 + 3 slices holds the coarsest level's mips. Between an
// update and its finishVoxelization(), a direction's word that receives light holds a tagged light entry
// (vctTagLightEntry) instead of radiance.
#ifndef BRICKLIGHT_VCT_LAYOUT_GLSL
#define BRICKLIGHT_VCT_LAYOUT_GLSL

// Opacity words: how much of a voxel's cross-section blocks light travelling along x, y and z, 8-bit fixed
// point each (bits 0–7, 8–15, 16–23: the RGB of the RGBA8_UNORM view; VXGI 1.0's directional opacity). A surface
// blocks light along each axis by the normal's component on it (a wall across x blocks x fully and y, z not at
// all); downsampling keeps the axes apart, so that a wall across a coarse voxel still blocks a cone crossing it.
const uint BL_VCT_OPACITY_AXIS_ONE = 255u;
uint vctPackOpacity(vec3 a) {
    // precise: no fused multiply-add, so that Vulkan and GL round a value near a half unit alike.
    precise vec3 scaled = clamp(a, 0.0, 1.0) * float(BL_VCT_OPACITY_AXIS_ONE) + 0.5;
    uvec3 q = uvec3(scaled);
    return q.x | (q.y << 8u) | (q.z << 16u);
}
uint vctMaxOpacity(uint a, uint b) {
    uvec3 m = max(uvec3(a, a >> 8u, a >> 16u) & 255u, uvec3(b, b >> 8u, b >> 16u) & 255u);
    return m.x | (m.y << 8u) | (m.z << 16u);
}
// A parent's opacity words from its 2³ children's (child i at 2·voxel + (i & 1, (i >> 1) & 1, i >> 2)): along each
// axis the two children of each column combine as complements, 1 − (1 − a)(1 − b), and the four columns average.
// In integers (255² units per column), rounded half up: the same word on every device, whatever its float
// division.
uint vctDownsampleOpacity(uint children[8]) {
    uint word = 0u;
    for (int axis = 0; axis < 3; ++axis) {
        uint shift = 8u * uint(axis), sum = 0u;
        for (int j = 0; j < 4; ++j) {
            // The j-th column along `axis`: its lower child has the axis bit clear.
            int lower = axis == 0 ? 2 * j : (axis == 1 ? (j & 1) + 4 * (j >> 1) : j);
            int upper = lower + (1 << axis);
            uint a = (children[lower] >> shift) & 255u, b = (children[upper] >> shift) & 255u;
            sum += 65025u - (255u - a) * (255u - b);
        }
        word |= ((sum + 510u) / 1020u) << shift;
    }
    return word;
}
// A product with the folded constant, not a division: compilers turn `/ 255.0` into a division on one device and a
// reciprocal's product on another, and the light the downsampling weights by it must round alike.
vec3 vctUnpackOpacity(uint w) {
    precise vec3 a = vec3(uvec3(w, w >> 8u, w >> 16u) & uvec3(BL_VCT_OPACITY_AXIS_ONE)) * (1.0 / 255.0);
    return a;
}
// Counters (Clipmap::readCounters): which word counts what.
const uint BL_VCT_COUNT_FRAGMENTS = 0u;          // voxelization fragments shaded
const uint BL_VCT_COUNT_OFF_TRIANGLE = 1u;       // fragments of the dilated quad whose pixel misses the triangle
const uint BL_VCT_COUNT_VOXELS_WRITTEN = 2u;     // opacity writes (one per voxel a fragment covers)
const uint BL_VCT_COUNT_KILLED_BY_FINER = 3u;    // voxels left to downsampling (inside the finer level)
const uint BL_VCT_COUNT_KILLED_NOT_DIRTY = 4u;   // voxels outside this frame's rewrite boxes
const uint BL_VCT_COUNT_EMITTANCE_WRITES = 5u;   // voxels that received emittance
const uint BL_VCT_COUNT_LIGHT_DROPPED = 6u;      // light writes dropped: their sub-pool of light entries was full (always counted)
const uint BL_VCT_COUNTER_COUNT = 8u;
// A light pool entry sums, besides the light, the projected coverage of the surfaces that sent it, in these units per
// voxel face (voxelize.glsl's blVoxelAddLight; resolve_light.comp reads it).
const float VCT_COVERAGE_UNITS = 65536.0;
// The light pool's sub-pools (voxelize.glsl's blVoxelLightEntry): their claim counters follow the counters above.
const uint BL_VCT_LIGHT_POOLS = 64u;
const uint BL_VCT_COUNTER_POOLS = 8u;

// While an update writes, a direction's atlas word that holds a light entry's index is tagged so that it cannot be
// radiance: exponent 1 with every mantissa below 256, which canonical RGB9E5 (bricklight/rgb9e5.glsl) never is. So
// the words need no clear before an update: an untagged word is last update's radiance, and the resolve overwrites
// it. Indices up to 2^24 − 1.
uint vctTagLightEntry(uint entry) { return (1u << 27u) | (entry & 255u) | (((entry >> 8u) & 255u) << 9u) | (((entry >> 16u) & 255u) << 18u); }
bool vctIsLightEntry(uint word) { return (word >> 27u) == 1u && (word & ((1u << 8u) | (1u << 17u) | (1u << 26u))) == 0u; }
uint vctLightEntryOf(uint word) { return (word & 255u) | (((word >> 9u) & 255u) << 8u) | (((word >> 18u) & 255u) << 16u); }

// A box of world voxels of one level: [minLevel.xyz, max.xyz), the level in minLevel.w.
struct BlVctBox {
    ivec4 minLevel;
    ivec4 max;
};

// What changes with the anchor: written by Clipmap::update, read by every voxelization draw.
#define BL_VCT_FRAME_BLOCK(slot)                                                                          \
    BL_READ_BUFFER(slot) BlVctFrame {                                                                     \
        ivec4 origin[8];  /* each level's lowest world voxel */                                          \
        uvec4 params;     /* x resolution, y levels, z emittance directions (0, 1, 6), w boxes */       \
        vec4 scales;      /* x finest voxel size, y fixed-point light units per unit of radiance */     \
        uvec4 flags;      /* x 1: count (BL_VCT_COUNT_*), y mips of the coarsest level, z light entries per sub-pool */ \
        BlVctBox boxes[]; /* the voxels this frame's voxelization may write */                           \
    } blVctFrame

// Where a region starts in x.
int vctRegionX(uint region, uint resolution) { return int(region * (resolution + 2u)); }

// A world voxel's texel in a region's level: toroidal, past the border column and slice.
ivec3 vctTexel(uint region, uint level, ivec3 worldVoxel, uint resolution) {
    ivec3 t = worldVoxel & ivec3(int(resolution) - 1);  // a power of two: the positive modulo, also below zero
    return t + ivec3(vctRegionX(region, resolution) + 1, 0, int(level * (resolution + 2u)) + 1);
}

// The atlas's slices in all, and where mip m ≥ 1 of the coarsest level lies in a region (add the region's x
// offset, vctRegionX): a box of (resolution >> m) + 3 texels per axis, not toroidal, texel t holding the mip's world
// voxel (coarsest origin >> m) − 1 + t, so that it covers the whole coarsest level (whose origin need not align
// with the mip's voxels) with an empty border on every side for filtering. Mip 1 lies at the slab's corner, the
// others beside it, stacked in y.
int vctTracedSlices(uint levels, uint resolution) { return int(levels * (resolution + 2u) + resolution / 2u + 3u); }
ivec3 vctMipBoxOffset(uint mip, uint levels, uint resolution) {
    int r = int(resolution), m = int(mip);
    // Mips 2 .. mip − 1 below this one: Σ (r >> k) + 3 = r / 2 − (r >> (mip − 1)) + 3 (mip − 2).
    ivec3 beside = ivec3(r / 2 + 3, r / 2 - (r >> max(m - 1, 0)) + 3 * (m - 2), 0);
    return (mip <= 1u ? ivec3(0) : beside) + ivec3(0, 0, int(levels * (resolution + 2u)));
}
// Regions of the atlas for 0, 1 or 6 emittance directions: opacity, then one per direction.
uint vctRegions(uint directions) { return 1u + directions; }

// The six emittance directions of the anisotropic mode, in storage order.
vec3 vctDirection(uint d) {
    vec3 axis = vec3(equal(uvec3(d % 3u), uvec3(0u, 1u, 2u)));
    return d < 3u ? axis : -axis;
}

#endif
