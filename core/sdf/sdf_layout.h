// C++ mirror of include/bricklight/sdf_layout.glsl and shaders/sdf/build_common.glsl: the numbers
// that the builder's records and the shaders must agree on.
#pragma once

#include <cstdint>

#include "bricklight/sdf.h"

namespace bricklight::sdf::layout {

constexpr uint32_t kCascadeVoxels = kCascadeResolution * kCascadeResolution * kCascadeResolution;
constexpr uint32_t kBrickTexels = kBrickResolution * kBrickResolution * kBrickResolution;

constexpr uint32_t kEmpty = 0xFFFFFFFEu;
constexpr uint32_t kUnbuilt = 0xFFFFFFFFu;
constexpr uint32_t kFirstState = 0xFFFFFFF0u;
constexpr uint32_t kNoBase = 0xFFFFFFFCu;  // base map: no static brick kept aside (BL_SDF_NO_BASE)
static_assert(kNoBase == FieldSnapshot::kNoBase);
constexpr uint32_t kAabbNone = 0xFFFFFFFFu;
// Brick AABB flag: the brick holds surfaces of alpha-tested instances (InstanceDesc::alphaTested). The brick
// AABB buffer holds capacity words of boxes, then two words per brick: the 4³ cells opaque surfaces reach.
constexpr uint32_t kAabbAlphaTested = 1u << 30;
static_assert(kAabbAlphaTested == FieldSnapshot::kAabbAlphaTested);
constexpr uint32_t kOpaqueCellWords = 2;
// Then two words per brick: its surface material (albedo RGBA8, emission RGB9E5; FieldSnapshot::brickMaterials).
constexpr uint32_t kMaterialWords = 2;
constexpr uint32_t kBrickInfoWords = 1 + kOpaqueCellWords + kMaterialWords;  // per brick, in the AABB buffer
// Per-update material table: two vec4 per gathered instance (albedo, emission), indexed by the triangles' tag.
constexpr uint32_t kMaterialTableBytesPerInstance = 32;
// Brick owner entries: cascade << 24 | allocation generation << 18 | physical voxel index.
constexpr uint32_t kNoOwner = 0xFFFFFFFFu;
constexpr uint32_t kOwnerGenerationShift = 18;
constexpr uint32_t kOwnerVoxelMask = 0x3FFFFu;
static_assert(kCascadeVoxels - 1 <= kOwnerVoxelMask, "a physical voxel index fits below the generation bits");

constexpr uint32_t kTreeStride = 4616;  // uints per cascade
constexpr uint32_t kTreeMid = 4096;
constexpr uint32_t kTreeRoot = 4608;

// Counters (uint indices).
enum Counter : uint32_t {
    FreeCount = 0,
    AllocCursor,
    RefCursor,
    TouchedCount,
    SortedCursor,
    BricksAllocated,
    BricksFreed,
    TrianglesRejected,
    VoxelsDeferred,
    VoxelsBuilt,
    TrianglesProcessed,
    RefsStored,
    FreeAtAllocation,
    RefsInUpdate,
    SplitCursor,
    SplitWorkCursor,
    BricksSplit,
    CounterCount = 20
};

// The brick pass splits a brick with more references than this into chunks of this many, one group each,
// for at most kMaxSplitBricks bricks per round (build_common.glsl).
constexpr uint32_t kRefsPerGroup = 2048;
constexpr uint32_t kMaxSplitBricks = 2048;
constexpr uint32_t kSplitMinimumClear = 0x7F800000u;  // +inf

// Indirect argument offsets (bytes) in the args buffer.
constexpr uint64_t kArgsPerTouched64 = 0;
constexpr uint64_t kArgsPerTouchedBrick = 12;
constexpr uint64_t kArgsPerReference64 = 24;
constexpr uint64_t kArgsPerSplitBrick = 36;
constexpr uint64_t kArgsBytes = 48;

constexpr uint32_t kWideGroups = 32768;

// Mover grids (mover_grid.glsl).
constexpr float kMoverTag = 2.0f;
constexpr uint32_t kMoverMaxTriangles = 1u << 20;    // triangle bits of a key
constexpr uint64_t kMoverMaxSamples = 1ull << 23;    // per grid (32 MiB of keys); larger meshes re-voxelize
constexpr int kMoverMarginCells = 10;                // lattice beyond the mesh's bounds: > the keys' reach
constexpr int kMoverChunkVoxels = 4;                 // a chunk references at most 4³ voxels  // dispatches wider than this use a second dimension

struct GpuCascade {
    int32_t origin[4];    // xyz origin voxel, w: exists
    float voxelSize[4];   // size, 1/size, hit epsilon, band (world units)
};
struct GpuCascadeTable {
    uint32_t header[4];   // cascade count, atlas bricks per axis, brick capacity, 0
    GpuCascade cascades[kMaxCascades];
};
static_assert(sizeof(GpuCascadeTable) == 16 + 32 * kMaxCascades);

// Job table head: per cascade min (w: has jobs), max; then per job min (w: cascade), size (w: first voxel).
struct GpuInt4 {
    int32_t v[4];
};
constexpr uint32_t kJobTableHeadInts = 2 * kMaxCascades;

// Hit threshold of the tracer, in brixel intervals: trilinear interpolation of an unsigned distance can
// stay up to half an interval above zero at a surface, so the threshold must exceed 0.5.
constexpr float kHitEpsilonBrixels = 0.6f;

}  // namespace bricklight::sdf::layout
