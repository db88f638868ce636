// Layout of the sparse brick distance field's GPU resources, shared by the builder passes (shaders/sdf)
// and the public trace API (trace.glsl). The C++ side mirrors these numbers in core/sdf/sdf_layout.h.
#ifndef BRICKLIGHT_SDF_LAYOUT_GLSL
#define BRICKLIGHT_SDF_LAYOUT_GLSL

#define BL_SDF_MAX_CASCADES 16u
#define BL_SDF_CASCADE_RES 64
#define BL_SDF_CASCADE_VOXELS 262144u  // 64³
#define BL_SDF_BRICK_RES 8
// Distances saturate at this many brixel intervals (voxel / 7); stored as distance / band in R8_UNORM.
#define BL_SDF_BAND_BRIXELS 2.0

// Brick map entries: a brick id, or one of these states.
#define BL_SDF_EMPTY 0xFFFFFFFEu     // built, no surface within the band of the voxel
#define BL_SDF_UNBUILT 0xFFFFFFFFu   // not built yet (or deferred): tracing falls to a coarser cascade
#define BL_SDF_BUILDING 0xFFFFFFFDu  // being built by the current update (internal)
// Base map entries (internal to the builder): the brick (or EMPTY) holding a voxel's static geometry alone
// where dynamic instances' distances are composited into its live brick, else this.
#define BL_SDF_NO_BASE 0xFFFFFFFCu
#define BL_SDF_FIRST_STATE 0xFFFFFFF0u

// Per-brick owner (SdfScene::brickOwnerBuffer): cascade << 24 | allocation generation << 18 | physical
// voxel index (< 64³ = 2^18), or BL_SDF_NO_OWNER for a brick never allocated. The generation counts the
// brick's allocations (mod 64), so that a brick freed and given back to the same voxel by one update (the
// builder frees a rebuilt region's bricks and hands them out again in whatever order the GPU's atomics
// take) reads as a new owner all the same.
#define BL_SDF_NO_OWNER 0xFFFFFFFFu
#define BL_SDF_OWNER_GENERATION_SHIFT 18u
#define BL_SDF_OWNER_GENERATIONS 64u
#define BL_SDF_OWNER_VOXEL_MASK 0x3FFFFu

// Per-brick tight AABB: 3 bits per axis min, then max, in brixel sample indices (0..7).
#define BL_SDF_AABB_NONE 0xFFFFFFFFu  // brick holds distances but no surface
// Flag beside the box: the brick holds surfaces of alpha-tested instances (sdf::InstanceDesc::alphaTested).
// The AABB buffer then continues, after header.z (the capacity) words, with two words per brick: bit
// (z·4 + y)·4 + x set where an opaque surface reaches that 4³ cell of the voxel (hits there are opaque).
#define BL_SDF_AABB_ALPHA_TESTED 0x40000000u
#define BL_SDF_OPAQUE_CELL_WORDS 2u
// After the cells, two words per brick: the surface material (sdf::FieldSnapshot::brickMaterials).
#define BL_SDF_MATERIAL_WORDS 2u

// AABB tree of one cascade, in a uint array with this stride per cascade:
//   [0, 4096)      bottom nodes 16³ (4³ voxels each): 5-bit min/max per axis in brixel intervals (0..28)
//                  relative to the node; BL_SDF_NODE_EMPTY if nothing (unbuilt voxels count as full)
//   [4096, 4608)   mid nodes 4³ (16³ voxels each): 8 floats (min.xyz, 0, max.xyz, 0), logical voxel units
//   [4608, 4616)   root: the same 8 floats
#define BL_SDF_TREE_STRIDE 4616u
#define BL_SDF_TREE_MID 4096u
#define BL_SDF_TREE_ROOT 4608u
#define BL_SDF_NODE_EMPTY 0xFFFFFFFFu

// Cascade table (a read buffer): header then one entry per cascade.
struct BlSdfCascade {
    ivec4 origin;      // xyz: world voxel coordinates of logical voxel 0; w: 1 if the cascade exists
    vec4 voxelSize;    // x: voxel size, y: 1 / voxel size, z: hit epsilon (world), w: band (world)
};
#define BL_SDF_CASCADE_TABLE_BODY \
    uvec4 header;  /* x: cascade count, y: atlas bricks per axis, z: brick capacity */ \
    BlSdfCascade cascades[BL_SDF_MAX_CASCADES];

// Physical (toroidal) index of a world voxel within its cascade's brick map.
uint blSdfPhysicalIndex(ivec3 worldVoxel) {
    ivec3 p = worldVoxel & ivec3(BL_SDF_CASCADE_RES - 1);
    return uint((p.z * BL_SDF_CASCADE_RES + p.y) * BL_SDF_CASCADE_RES + p.x);
}

// Brick id -> first texel of its 8³ block in the atlas.
ivec3 blSdfBrickTexel(uint brick, uint bricksPerAxis) {
    uint x = brick % bricksPerAxis;
    uint y = (brick / bricksPerAxis) % bricksPerAxis;
    uint z = brick / (bricksPerAxis * bricksPerAxis);
    return ivec3(x, y, z) * BL_SDF_BRICK_RES;
}

uvec3 blSdfAabbMin(uint bits) { return uvec3(bits, bits >> 3, bits >> 6) & 7u; }
uvec3 blSdfAabbMax(uint bits) { return uvec3(bits >> 9, bits >> 12, bits >> 15) & 7u; }

#endif
