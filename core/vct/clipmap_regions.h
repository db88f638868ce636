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
    glm::uvec4 params;  // resolution, levels, emittance words per voxel, boxes
    glm::vec4 scales;   // finest voxel size, fixed-point units per unit of radiance
    glm::uvec4 flags;   // x: counters on, y: mips of the coarsest level
};
struct FrameBox {
    glm::ivec4 minLevel, max;
};
static_assert(sizeof(FrameHeader) == 176 && sizeof(FrameBox) == 32);
constexpr uint64_t kFrameBufferBytes = sizeof(FrameHeader) + kMaxFrameBoxes * sizeof(FrameBox);
constexpr uint32_t kCounterWords = 8;
// Fixed-point units of emittance per unit of radiance at emittanceStorageScale 1.
constexpr float kEmittanceUnits = 65536.0f;

// The traced volumes' layout (vctTracedSlices / vctMipBoxOffset in vct_layout.glsl): slices in all, and where
// mip m ≥ 1 of the coarsest level lies, its box (resolution >> m) + 3 texels wide.
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
