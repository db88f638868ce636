// The clip-map's placement (include/bricklight/vct.h) against brute force on small levels: what a move
// reports as entered is exactly the voxels the level gained, the levels nest and align for downsampling,
// and toroidal texels are a bijection.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <set>
#include <tuple>

#include "bricklight/vct.h"
#include "../../core/vct/clipmap_regions.h"

using namespace bricklight::vct;
using bricklight::Error;

namespace {

using Voxel = std::tuple<int, int, int>;

std::set<Voxel> voxelsOf(const VoxelBox& b) {
    std::set<Voxel> s;
    for (int z = b.min.z; z < b.max.z; ++z)
        for (int y = b.min.y; y < b.max.y; ++y)
            for (int x = b.min.x; x < b.max.x; ++x) s.insert({x, y, z});
    return s;
}

ClipmapPlacement placement(uint32_t levels = 3, uint32_t resolution = 32, float voxel = 0.5f) {
    ClipmapDesc d;
    d.levels = levels;
    d.resolution = resolution;
    d.finestVoxelSize = voxel;
    Error error;
    auto p = ClipmapPlacement::create(d, &error);
    INFO(error.message);
    REQUIRE(p);
    return *p;
}

}  // namespace

TEST_CASE("clip-map descriptions outside the supported range are refused with the field named", "[vct][cpu]") {
    Error error;
    ClipmapDesc d;
    CHECK(checkClipmapDesc(d, &error));
    CHECK(clipmapMipLevels(d) == 5);  // 128³: down to 4³
    d.levels = 9;
    CHECK_FALSE(checkClipmapDesc(d, &error));
    CHECK(error.message.find("levels 9") != std::string::npos);
    d = {};
    d.resolution = 96;
    CHECK_FALSE(checkClipmapDesc(d, &error));
    CHECK(error.message.find("resolution 96") != std::string::npos);
    d = {};
    d.finestVoxelSize = -1.0f;
    CHECK_FALSE(checkClipmapDesc(d, &error));
    CHECK(error.message.find("finestVoxelSize") != std::string::npos);
    d.finestVoxelSize = 3e37f;  // the coarsest level's width would not be finite
    CHECK_FALSE(checkClipmapDesc(d, &error));
    d = {};
    d.mipLevels = 8;  // 128 has 7 halvings
    CHECK_FALSE(checkClipmapDesc(d, &error));
    CHECK(error.message.find("mipLevels 8") != std::string::npos);
    CHECK_FALSE(ClipmapPlacement::create(d, &error));
    d = {};
    d.multiBounce = true;
    d.emittance = EmittanceMode::None;  // no light to bounce
    CHECK_FALSE(checkClipmapDesc(d, &error));
    CHECK(error.message.find("multiBounce") != std::string::npos);
}

TEST_CASE("the clip-map's memory: one atlas and a light pool, 128³ × 5 with six directions within 350 MiB", "[vct][cpu]") {
    ClipmapDesc d;  // 128³ × 5, six directions
    // 7 regions of 130 × 128 × (5 × 130 + 67) words; the light pool: an eighth of the voxels, 12 bytes each; the
    // raster-size target, the frame (176 + 64 boxes × 32 bytes), the counters (8 + 64 words), the 1³ bounce stand-in.
    const uint64_t atlas = 7ull * 130 * 128 * 717 * 4, light = 128ull * 128 * 128 * 5 / 8 * 12, fixed = 128 * 128 * 4 + (176 + 64 * 32) + 72 * 4;
    CHECK(clipmapBytes(d) == atlas + light + fixed + 4);
    CHECK(clipmapBytes(d) <= 350ull << 20);
    d.multiBounce = true;  // a copy for the bounce cones
    CHECK(clipmapBytes(d) == 2 * atlas + light + fixed);
    d.multiBounce = false;
    d.lightEntries = 64 * 1000;
    CHECK(clipmapBytes(d) == atlas + 64 * 1000 * 12 + fixed + 4);
    d.lightEntries = (1u << 24) + 1;  // past the tagged index's 24 bits
    Error error;
    CHECK_FALSE(checkClipmapDesc(d, &error));
    CHECK(error.message.find("lightEntries") != std::string::npos);
    d = {};
    d.emittance = EmittanceMode::Isotropic;
    CHECK(clipmapBytes(d) == 2ull * 130 * 128 * 717 * 4 + light + fixed + 4);
    d.emittance = EmittanceMode::None;  // no light pool (a 16-byte stand-in)
    CHECK(clipmapBytes(d) == 1ull * 130 * 128 * 717 * 4 + 16 + fixed + 4);
}
