// The clip-map's geometry (include/bricklight/vct.h): description checks, level placement around the
// anchor and the slabs a move uncovers.
#include <algorithm>
#include <cmath>

#include "bricklight/vct.h"
#include "clipmap_regions.h"
#include "../common/refusal.h"

namespace bricklight::vct {

namespace {

// World voxel coordinates stay well inside int32 (toroidal addressing and box arithmetic never overflow):
// an anchor further than this many finest voxels from the world origin is refused.
constexpr double kMaxAnchorVoxels = double(1 << 28);

bool isPowerOfTwo(uint32_t v) { return v && !(v & (v - 1)); }

}  // namespace

uint64_t VoxelBox::voxelCount() const {
    const glm::ivec3 e = max - min;
    return e.x <= 0 || e.y <= 0 || e.z <= 0 ? 0 : uint64_t(e.x) * uint64_t(e.y) * uint64_t(e.z);
}

bool checkClipmapDesc(const ClipmapDesc& d, Error* error) {
    const bricklight::detail::Refusal fail(error, "clip-map");
    if (d.levels < kMinLevels || d.levels > kMaxLevels)
        return fail("levels " + std::to_string(d.levels) + " is outside " + std::to_string(kMinLevels) + ".." + std::to_string(kMaxLevels));
    if (!isPowerOfTwo(d.resolution) || d.resolution < 32 || d.resolution > 256)
        return fail("resolution " + std::to_string(d.resolution) + " must be 32, 64, 128 or 256");
    if (!(d.finestVoxelSize > 0.0f) || !std::isfinite(d.finestVoxelSize) ||
        !std::isfinite(d.finestVoxelSize * float(d.resolution) * float(1u << (d.levels - 1))))  // the coarsest level's width
        return fail("finestVoxelSize must be a positive number whose coarsest level is finite (got " +
                    std::to_string(d.finestVoxelSize) + ")");
    const uint32_t fullChain = uint32_t(std::log2(double(d.resolution)));  // down to 1³
    if (d.mipLevels > fullChain)
        return fail("mipLevels " + std::to_string(d.mipLevels) + " is more than the " + std::to_string(fullChain) +
                    " mips a level of " + std::to_string(d.resolution) + "³ has", ErrorCode::OverBudget);
    if (d.emittance != EmittanceMode::None && d.emittance != EmittanceMode::Isotropic &&
        d.emittance != EmittanceMode::Anisotropic)
        return fail("emittance mode " + std::to_string(int(d.emittance)) + " is not None, Isotropic or Anisotropic");
    if (!(d.emittanceStorageScale > 0.0f) || !std::isfinite(d.emittanceStorageScale))
        return fail("emittanceStorageScale must be a positive finite number (got " + std::to_string(d.emittanceStorageScale) + ")");
    if (d.lightEntries > (uint64_t(1) << 24))
        return fail("lightEntries " + std::to_string(d.lightEntries) + " is more than 2^24", ErrorCode::OverBudget);
    if (d.multiBounce && d.emittance == EmittanceMode::None)
        return fail("multiBounce needs emittance (the mode is None): there is no light to bounce");
    return true;
}

uint32_t emittanceDirections(EmittanceMode mode) {
    return mode == EmittanceMode::Anisotropic ? 6u : mode == EmittanceMode::Isotropic ? 1u : 0u;
}

uint64_t clipmapBytes(const ClipmapDesc& d) {
    const uint64_t atlas = uint64_t(detail::atlasRegions(d.emittance)) * detail::regionWidth(d.resolution) * d.resolution *
                           detail::tracedSlices(d.levels, d.resolution) * 4;
    const uint64_t rasterSize = uint64_t(d.resolution) * d.resolution * 4;
    const uint64_t bounce = d.multiBounce ? atlas : 4;  // the copy of the previous frame's atlas, or the 1³ zero stand-in
    const uint64_t light = std::max<uint64_t>(detail::lightEntriesPerPool(d) * detail::kLightPools * 16, 16);
    const uint64_t frame = detail::kFrameBufferBytes, counters = detail::kCounterWords * 4;
    return atlas + bounce + light + rasterSize + frame + counters;
}

uint32_t clipmapMipLevels(const ClipmapDesc& d) {
    return d.mipLevels ? d.mipLevels : uint32_t(std::log2(double(d.resolution))) - 2;
}

std::optional<ClipmapPlacement> ClipmapPlacement::create(const ClipmapDesc& desc, Error* error) {
    if (!checkClipmapDesc(desc, error)) return std::nullopt;
    ClipmapPlacement p(desc);
    p.origins_.assign(desc.levels, glm::ivec3(0));
    return p;
}

float ClipmapPlacement::voxelSize(uint32_t level) const { return desc_.finestVoxelSize * float(1u << level); }

glm::ivec3 ClipmapPlacement::voxelAt(uint32_t level, const glm::vec3& point) const {
    const glm::dvec3 v = glm::floor(glm::dvec3(point) / double(voxelSize(level)));
    return glm::ivec3(v);
}

bool ClipmapPlacement::contains(uint32_t level, const glm::ivec3& voxel) const {
    const glm::ivec3 o = origins_[level];
    const int r = int(desc_.resolution);
    return voxel.x >= o.x && voxel.y >= o.y && voxel.z >= o.z && voxel.x < o.x + r && voxel.y < o.y + r && voxel.z < o.z + r;
}

glm::ivec3 ClipmapPlacement::toroidalTexel(const glm::ivec3& voxel) const {
    // The resolution is a power of two: & is the positive modulo, also for negative coordinates.
    const int mask = int(desc_.resolution) - 1;
    return {voxel.x & mask, voxel.y & mask, voxel.z & mask};
}

std::optional<std::vector<LevelUpdate>> ClipmapPlacement::moveAnchor(const glm::vec3& anchor, Error* error) {
    const glm::dvec3 inFinest = glm::dvec3(anchor) / double(desc_.finestVoxelSize);
    if (!std::isfinite(anchor.x) || !std::isfinite(anchor.y) || !std::isfinite(anchor.z) ||
        glm::any(glm::greaterThan(glm::abs(inFinest), glm::dvec3(kMaxAnchorVoxels)))) {
        if (error)
            *error = {ErrorCode::InvalidArgument, "clip-map: the anchor (" + std::to_string(anchor.x) + ", " + std::to_string(anchor.y) + ", " +
                     std::to_string(anchor.z) + ") is not finite or lies more than 2^28 finest voxels from the origin"};
        return std::nullopt;
    }
    const int r = int(desc_.resolution);
    std::vector<LevelUpdate> updates;
    for (uint32_t level = 0; level < desc_.levels; ++level) {
        // The centre voxel snapped to an even coordinate; the level spans resolution voxels around it.
        const glm::ivec3 centre = voxelAt(level, anchor);
        const glm::ivec3 even = (centre >> 1) << 1;  // arithmetic shift: floor to even, also below zero
        LevelUpdate u;
        u.level = level;
        u.origin = even - glm::ivec3(r / 2);
        const VoxelBox now{u.origin, u.origin + glm::ivec3(r)};
        const VoxelBox before{origins_[level], origins_[level] + glm::ivec3(r)};
        if (!placed_) u.entered.push_back(now);
        else if (u.origin != origins_[level]) u.entered = detail::uncovered(before, now);
        origins_[level] = u.origin;
        updates.push_back(std::move(u));
    }
    placed_ = true;
    return updates;
}

}  // namespace bricklight::vct
