// Box arithmetic of the clip-map (internal): the slabs a move uncovers, and per update which voxels the
// voxelization rewrites and which the downsampling refills.
#pragma once

#include <algorithm>
#include <optional>
#include <vector>

#include "bricklight/vct.h"

namespace bricklight::vct::detail {

// At most this many boxes reach the draws per update; beyond it each level's boxes merge into one.
constexpr size_t kMaxFrameBoxes = 64;

// The frame buffer's layout (BL_VCT_FRAME_BLOCK in include/bricklight/vct_layout.glsl, std430).
struct FrameHeader {
    glm::ivec4 origin[kMaxLevels];
    glm::uvec4 params;  // resolution, levels, emittance directions, boxes
    glm::vec4 scales;   // finest voxel size, fixed-point light units per unit of radiance
    glm::uvec4 flags;   // x: counters on, y: mips of the coarsest level, z: light entries per sub-pool
};
struct FrameBox {
    glm::ivec4 minLevel, max;
};
static_assert(sizeof(FrameHeader) == 176 && sizeof(FrameBox) == 32);
constexpr uint64_t kFrameBufferBytes = sizeof(FrameHeader) + kMaxFrameBoxes * sizeof(FrameBox);
// Statistics (VoxelizationCounters), then the light pool's claim counters (vct_layout.glsl).
constexpr uint32_t kStatisticWords = 8, kLightPools = 64, kCounterWords = kStatisticWords + kLightPools;
constexpr uint32_t kLightDroppedWord = 6;  // BL_VCT_COUNT_LIGHT_DROPPED: from here on, reset by update() only
// Fixed-point units of light per unit of radiance at emittanceStorageScale 1.
constexpr float kEmittanceUnits = 65536.0f;
// Entries of the light pool (four words each) per sub-pool: ClipmapDesc::lightEntries, or an eighth of the voxels but
// at least 65536 (a small clip-map's surfaces are a larger share of its voxels, and a small sub-pool fills unevenly).
inline uint64_t lightEntriesPerPool(const ClipmapDesc& d) {
    if (d.emittance == EmittanceMode::None) return 0;
    const uint64_t voxels = uint64_t(d.resolution) * d.resolution * d.resolution * d.levels;
    const uint64_t entries = d.lightEntries ? d.lightEntries : std::min<uint64_t>(std::max<uint64_t>(voxels / 8, 65536), uint64_t(1) << 24);  // tagged indices: 24 bits
    return std::max<uint64_t>(entries / kLightPools, 1);
}

// The atlas's layout (vct_layout.glsl): its regions, their width, slices in all, and where mip m ≥ 1 of the
// coarsest level lies within a region, its box (resolution >> m) + 3 texels wide.
inline uint32_t atlasRegions(EmittanceMode mode) { return 1 + emittanceDirections(mode); }
inline uint32_t regionWidth(uint32_t resolution) { return resolution + 2; }
inline uint32_t tracedSlices(uint32_t levels, uint32_t resolution) { return levels * (resolution + 2) + resolution / 2 + 3; }
inline glm::ivec3 mipBoxOffset(uint32_t mip, uint32_t levels, uint32_t resolution) {
    const int r = int(resolution), m = int(mip);
    const glm::ivec3 beside(r / 2 + 3, r / 2 - (r >> std::max(m - 1, 0)) + 3 * (m - 2), 0);
    return (mip <= 1 ? glm::ivec3(0) : beside) + glm::ivec3(0, 0, int(levels * (resolution + 2)));
}
inline int mipBoxSize(uint32_t mip, uint32_t resolution) { return int(resolution >> mip) + 3; }

// The parts of `now` not in `before`, as up to three disjoint slabs.
std::vector<VoxelBox> uncovered(const VoxelBox& before, const VoxelBox& now);
std::optional<VoxelBox> intersect(const VoxelBox& a, const VoxelBox& b);

struct FrameRegions {
    // Cleared, then written by the draws (except voxels inside the finer level).
    std::vector<LevelBox> rewrite;
    // Inner voxels (inside the finer level) to refill from it, levels ≥ 1, in increasing level order.
    std::vector<LevelBox> downsample;
};

// `before`: each level's origin before the move (meaningless when !placedBefore); `updates`: the move's result.
// World boxes must be finite (checked by the caller).
FrameRegions frameRegions(const ClipmapDesc& desc, const std::vector<glm::ivec3>& before, bool placedBefore,
                          const std::vector<LevelUpdate>& updates, const std::vector<WorldBox>& invalidated);

}  // namespace bricklight::vct::detail
