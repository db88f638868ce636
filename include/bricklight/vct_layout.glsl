// The voxel clip-map's layout on the device (include/bricklight/vct.h), shared by our voxelization, clear and
// downsampling passes and by the application's voxelization fragment shader (bricklight/voxelize.glsl).
//
// Level L's voxels live in z slices [L × resolution, (L + 1) × resolution) of the opacity volume, a world voxel
// at its coordinates modulo the resolution (toroidal), so that a level keeps what it still covers while it
// scrolls. The emittance accumulation buffer holds `channels` words per voxel, word-major: word w of every texel
// (in the volume's texel order), then word w + 1 — so that neighbouring threads touch neighbouring words.
#ifndef BRICKLIGHT_VCT_LAYOUT_GLSL
#define BRICKLIGHT_VCT_LAYOUT_GLSL

// Opacity words: how much of a voxel's cross-section blocks light travelling along x, y and z, 10-bit fixed
// point each (bits 0–9, 10–19, 20–29; VXGI 1.0's directional opacity). A surface blocks light along each axis
// by the normal's component on it (a wall across x blocks x fully and y, z not at all); downsampling keeps the
// axes apart, so that a wall across a coarse voxel still blocks a cone crossing it.
const uint BL_VCT_OPACITY_AXIS_ONE = 1023u;
uint vctPackOpacity(vec3 a) {
    uvec3 q = uvec3(clamp(a, 0.0, 1.0) * float(BL_VCT_OPACITY_AXIS_ONE) + 0.5);
    return q.x | (q.y << 10u) | (q.z << 20u);
}
uint vctMaxOpacity(uint a, uint b) {
    uvec3 m = max(uvec3(a, a >> 10u, a >> 20u) & 1023u, uvec3(b, b >> 10u, b >> 20u) & 1023u);
    return m.x | (m.y << 10u) | (m.z << 20u);
}
vec3 vctUnpackOpacity(uint w) {
    return vec3(uvec3(w, w >> 10u, w >> 20u) & uvec3(BL_VCT_OPACITY_AXIS_ONE)) / float(BL_VCT_OPACITY_AXIS_ONE);
}
// Counters (Clipmap::readCounters): which word counts what.
const uint BL_VCT_COUNT_FRAGMENTS = 0u;          // voxelization fragments shaded
const uint BL_VCT_COUNT_OFF_TRIANGLE = 1u;       // fragments of the dilated quad whose pixel misses the triangle
const uint BL_VCT_COUNT_VOXELS_WRITTEN = 2u;     // opacity writes (one per voxel a fragment covers)
const uint BL_VCT_COUNT_KILLED_BY_FINER = 3u;    // voxels left to downsampling (inside the finer level)
const uint BL_VCT_COUNT_KILLED_NOT_DIRTY = 4u;   // voxels outside this frame's rewrite boxes
const uint BL_VCT_COUNT_EMITTANCE_WRITES = 5u;   // voxels that received emittance
const uint BL_VCT_COUNTER_COUNT = 8u;

// A box of world voxels of one level: [minLevel.xyz, max.xyz), the level in minLevel.w.
struct BlVctBox {
    ivec4 minLevel;
    ivec4 max;
};

// What changes with the anchor: written by Clipmap::update, read by every voxelization draw.
#define BL_VCT_FRAME_BLOCK(slot)                                                                          \
    BL_READ_BUFFER(slot) BlVctFrame {                                                                     \
        ivec4 origin[8];  /* each level's lowest world voxel */                                          \
        uvec4 params;     /* x resolution, y levels, z emittance words per voxel (0, 3, 18), w boxes */  \
        vec4 scales;      /* x finest voxel size, y fixed-point units per unit of radiance */            \
        uvec4 flags;      /* x 1: count (BL_VCT_COUNT_*), y mips of the coarsest level */               \
        BlVctBox boxes[]; /* the voxels this frame's voxelization may write */                           \
    } blVctFrame

ivec3 vctTexel(uint level, ivec3 worldVoxel, uint resolution) {
    ivec3 t = worldVoxel & ivec3(int(resolution) - 1);  // a power of two: the positive modulo, also below zero
    return t + ivec3(0, 0, int(level * resolution));
}

// The texel's index in buffers laid out like the volume (x fastest, then y, then z).
uint vctTexelIndex(uint level, ivec3 worldVoxel, uint resolution) {
    uvec3 t = uvec3(vctTexel(level, worldVoxel, resolution));
    return (t.z * resolution + t.y) * resolution + t.x;
}

// Where word `word` of the texel `texelIndex` lies in the emittance buffer (texelCount: resolution³ × levels).
uint vctWordIndex(uint texelIndex, uint word, uint texelCount) { return word * texelCount + texelIndex; }

// The traced volumes (Clipmap::tracedOpacity / tracedEmittance) hold each level in z slices
// [L × (resolution + 2), (L + 1) × (resolution + 2)) — the level's voxels toroidally with a border slice each side —
// and above them one slab of resolution / 2 + 3 slices with the coarsest level's mips. Mip m (1, 2, …; voxels
// 2^m times the coarsest level's) is not toroidal: a box of (resolution >> m) + 3 texels per axis, texel t holding
// the mip's world voxel (coarsest origin >> m) − 1 + t, so that it covers the whole coarsest level (whose origin
// need not align with the mip's voxels) with an empty border on every side for filtering. Mip 1 lies at the slab's
// corner, the others beside it, stacked in y.
int vctTracedSlices(uint levels, uint resolution) { return int(levels * (resolution + 2u) + resolution / 2u + 3u); }
ivec3 vctMipBoxOffset(uint mip, uint levels, uint resolution) {
    int r = int(resolution), m = int(mip);
    // Mips 2 .. mip − 1 below this one: Σ (r >> k) + 3 = r / 2 − (r >> (mip − 1)) + 3 (mip − 2).
    ivec3 beside = ivec3(r / 2 + 3, r / 2 - (r >> max(m - 1, 0)) + 3 * (m - 2), 0);
    return (mip <= 1u ? ivec3(0) : beside) + ivec3(0, 0, int(levels * (resolution + 2u)));
}

// The six emittance directions of the anisotropic mode, in storage order.
vec3 vctDirection(uint d) {
    vec3 axis = vec3(equal(uvec3(d % 3u), uvec3(0u, 1u, 2u)));
    return d < 3u ? axis : -axis;
}

#endif
