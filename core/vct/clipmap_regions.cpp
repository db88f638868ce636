// Which voxels an update rewrites and which the downsampling refills (core/vct/clipmap_regions.h).
//
// Level L ≥ 1 is voxelized directly only outside level L − 1 (its "inner" box); inside, it is the
// downsampling of L − 1. So a level must rewrite what entered it, the invalidated boxes, and the inner voxels
// that left the finer level (they were downsampled, now they are voxelized); and it must refill every inner
// voxel whose children changed, or that it cleared itself.
#include <algorithm>
#include <cmath>

#include "clipmap_regions.h"

namespace bricklight::vct::detail {

std::vector<VoxelBox> uncovered(const VoxelBox& before, const VoxelBox& now) {
    std::vector<VoxelBox> slabs;
    VoxelBox rest = now;  // shrinks to the part still inside before's ranges on the axes done so far
    for (int axis = 0; axis < 3; ++axis) {
        if (rest.min[axis] < before.min[axis]) {  // a slab below
            VoxelBox s = rest;
            s.max[axis] = std::min(before.min[axis], rest.max[axis]);
            slabs.push_back(s);
            rest.min[axis] = s.max[axis];
        }
        if (rest.max[axis] > before.max[axis]) {  // a slab above
            VoxelBox s = rest;
            s.min[axis] = std::max(before.max[axis], rest.min[axis]);
            slabs.push_back(s);
            rest.max[axis] = s.min[axis];
        }
        if (rest.min[axis] >= rest.max[axis]) break;  // nothing of `now` overlaps `before`
    }
    return slabs;
}

std::optional<VoxelBox> intersect(const VoxelBox& a, const VoxelBox& b) {
    VoxelBox c{glm::max(a.min, b.min), glm::min(a.max, b.max)};
    if (c.voxelCount() == 0) return std::nullopt;
    return c;
}

namespace {

VoxelBox levelBox(const glm::ivec3& origin, int resolution) { return {origin, origin + glm::ivec3(resolution)}; }
// The finer level's footprint in this level's voxels (origins are even, so it is whole voxels).
VoxelBox innerBox(const glm::ivec3& finerOrigin, int resolution) {
    return {finerOrigin >> 1, (finerOrigin >> 1) + glm::ivec3(resolution / 2)};
}
// A box of level L − 1 in level L's voxels, covering every parent of its voxels.
VoxelBox parentsOf(const VoxelBox& b) { return {b.min >> 1, (b.max + 1) >> 1}; }

void addClipped(std::vector<VoxelBox>& to, const VoxelBox& box, const VoxelBox& clip) {
    if (auto c = intersect(box, clip)) to.push_back(*c);
}

VoxelBox bounds(const std::vector<VoxelBox>& boxes) {
    VoxelBox b = boxes.front();
    for (const VoxelBox& x : boxes) b = {glm::min(b.min, x.min), glm::max(b.max, x.max)};
    return b;
}

}  // namespace

FrameRegions frameRegions(const ClipmapDesc& desc, const std::vector<glm::ivec3>& before, bool placedBefore,
                          const std::vector<LevelUpdate>& updates, const std::vector<WorldBox>& invalidated) {
    const int r = int(desc.resolution);
    std::vector<std::vector<VoxelBox>> rewrite(desc.levels), refill(desc.levels);
    for (uint32_t level = 0; level < desc.levels; ++level) {
        const VoxelBox whole = levelBox(updates[level].origin, r);
        std::vector<VoxelBox>& out = rewrite[level];
        if (!desc.persistent) {
            out.push_back(whole);
        } else {
            for (const VoxelBox& b : updates[level].entered) addClipped(out, b, whole);
            if (placedBefore && level > 0) {
                const VoxelBox innerBefore = innerBox(before[level - 1], r), innerNow = innerBox(updates[level - 1].origin, r);
                for (const VoxelBox& b : uncovered(innerNow, innerBefore)) addClipped(out, b, whole);
            }
            const double size = double(desc.finestVoxelSize) * double(1u << level);
            for (const WorldBox& w : invalidated) {
                // Every voxel the box touches, and one more around it: the voxelization is conservative by up to a
                // voxel.
                const glm::dvec3 lo = glm::floor(glm::dvec3(w.min) / size) - 1.0, hi = glm::floor(glm::dvec3(w.max) / size) + 2.0;
                const glm::dvec3 clipLo(whole.min), clipHi(whole.max);
                const glm::dvec3 a = glm::clamp(lo, clipLo, clipHi), b = glm::clamp(hi, clipLo, clipHi);
                addClipped(out, VoxelBox{glm::ivec3(a), glm::ivec3(b)}, whole);
            }
        }
        if (level == 0) continue;
        const VoxelBox inner = innerBox(updates[level - 1].origin, r);
        for (const VoxelBox& b : rewrite[level - 1]) addClipped(refill[level], parentsOf(b), inner);
        for (const VoxelBox& b : refill[level - 1]) addClipped(refill[level], parentsOf(b), inner);
        for (const VoxelBox& b : out) addClipped(refill[level], b, inner);
    }
    size_t total = 0;
    for (const auto& boxes : rewrite) total += boxes.size();
    FrameRegions regions;
    for (uint32_t level = 0; level < desc.levels; ++level) {
        if (total > kMaxFrameBoxes && rewrite[level].size() > 1) rewrite[level] = {bounds(rewrite[level])};
        if (refill[level].size() > kMaxFrameBoxes) refill[level] = {bounds(refill[level])};
        for (const VoxelBox& b : rewrite[level]) regions.rewrite.push_back({level, b});
        for (const VoxelBox& b : refill[level]) regions.downsample.push_back({level, b});
    }
    return regions;
}

}  // namespace bricklight::vct::detail
