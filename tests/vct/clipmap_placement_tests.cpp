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
    // 7 regions of 130 × 128 × (5 × 130 + 67) words; the light pool: an eighth of the voxels, 16 bytes each; the
    // raster-size target, the frame (176 + 64 boxes × 32 bytes), the counters (8 + 64 words), the 1³ bounce stand-in.
    const uint64_t atlas = 7ull * 130 * 128 * 717 * 4, light = 128ull * 128 * 128 * 5 / 8 * 16, fixed = 128 * 128 * 4 + (176 + 64 * 32) + 72 * 4;
    CHECK(clipmapBytes(d) == atlas + light + fixed + 4);
    CHECK(clipmapBytes(d) <= 350ull << 20);
    d.multiBounce = true;  // a copy for the bounce cones
    CHECK(clipmapBytes(d) == 2 * atlas + light + fixed);
    d.multiBounce = false;
    d.lightEntries = 64 * 1000;
    CHECK(clipmapBytes(d) == atlas + 64 * 1000 * 16 + fixed + 4);
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

TEST_CASE("the first placement voxelizes every level whole; levels nest and align", "[vct][cpu]") {
    ClipmapPlacement p = placement(4, 32, 0.25f);
    Error error;
    const glm::vec3 anchor(3.3f, -7.9f, 0.6f);
    auto updates = p.moveAnchor(anchor, &error);
    REQUIRE(updates);
    REQUIRE(updates->size() == 4);
    for (const LevelUpdate& u : *updates) {
        REQUIRE(u.entered.size() == 1);
        CHECK(u.entered[0].voxelCount() == 32u * 32u * 32u);
        CHECK(u.origin.x % 2 == 0);
        CHECK(u.origin.y % 2 == 0);
        CHECK(u.origin.z % 2 == 0);
        CHECK(p.contains(u.level, p.voxelAt(u.level, anchor)));  // centred on the anchor
        if (u.level + 1 < 4) {
            // Level L in level L+1's voxels: whole voxels (the origin is even) and inside it.
            const glm::ivec3 lo = u.origin / 2, hi = (u.origin + glm::ivec3(32)) / 2 - glm::ivec3(1);
            CHECK(p.contains(u.level + 1, lo));
            CHECK(p.contains(u.level + 1, hi));
        }
    }
}

TEST_CASE("an anchor move reports exactly the voxels each level gained", "[vct][cpu]") {
    ClipmapPlacement p = placement(3, 32, 0.5f);
    Error error;
    std::mt19937 random(7);
    std::uniform_real_distribution<float> step(-9.0f, 9.0f);
    glm::vec3 anchor(0.2f, 1.7f, -3.1f);
    REQUIRE(p.moveAnchor(anchor, &error));
    uint64_t moves = 0, nothing = 0;
    for (int i = 0; i < 60; ++i) {
        std::vector<VoxelBox> before;
        for (uint32_t l = 0; l < 3; ++l) before.push_back({p.origin(l), p.origin(l) + glm::ivec3(32)});
        // Small steps (inside a voxel: nothing), slabs on one axis, diagonal moves, and jumps past a level.
        anchor += i % 5 == 0 ? glm::vec3(0.01f, 0.0f, 0.0f) : glm::vec3(step(random), step(random) * float(i % 2), step(random) * float(i % 3 == 0));
        if (i == 30) anchor += glm::vec3(100.0f, 0.0f, 0.0f);
        auto updates = p.moveAnchor(anchor, &error);
        REQUIRE(updates);
        for (const LevelUpdate& u : *updates) {
            const VoxelBox now{u.origin, u.origin + glm::ivec3(32)};
            std::set<Voxel> expected = voxelsOf(now);
            for (const Voxel& v : voxelsOf(before[u.level])) expected.erase(v);
            std::set<Voxel> reported;
            uint64_t count = 0;
            for (const VoxelBox& b : u.entered) {
                count += b.voxelCount();
                for (const Voxel& v : voxelsOf(b)) reported.insert(v);
            }
            INFO("move " << i << ", level " << u.level);
            CHECK(count == reported.size());  // the boxes are disjoint
            CHECK(reported == expected);
            ++moves;
            nothing += u.entered.empty();
        }
    }
    CHECK(nothing > 0);  // small steps moved some level by no voxel at all
    CHECK(moves == 180);
}

TEST_CASE("toroidal texels are a bijection over a level wherever it lies", "[vct][cpu]") {
    ClipmapPlacement p = placement(2, 32, 1.0f);
    Error error;
    for (const glm::vec3 anchor : {glm::vec3(0.0f), glm::vec3(-1000.5f, 37.2f, -3.0f), glm::vec3(12345.0f, -777.0f, 5.5f)}) {
        REQUIRE(p.moveAnchor(anchor, &error));
        for (uint32_t level = 0; level < 2; ++level) {
            std::set<Voxel> texels;
            const glm::ivec3 o = p.origin(level);
            for (const Voxel& v : voxelsOf({o, o + glm::ivec3(32)})) {
                const glm::ivec3 t = p.toroidalTexel({std::get<0>(v), std::get<1>(v), std::get<2>(v)});
                REQUIRE(glm::all(glm::greaterThanEqual(t, glm::ivec3(0))));
                REQUIRE(glm::all(glm::lessThan(t, glm::ivec3(32))));
                texels.insert({t.x, t.y, t.z});
            }
            CHECK(texels.size() == 32u * 32u * 32u);
        }
    }
}

TEST_CASE("a bad anchor is refused and changes nothing; invalidate voxelizes everything again", "[vct][cpu]") {
    ClipmapPlacement p = placement();
    Error error;
    REQUIRE(p.moveAnchor(glm::vec3(1.0f), &error));
    const glm::ivec3 origin = p.origin(0);
    CHECK_FALSE(p.moveAnchor(glm::vec3(std::nanf(""), 0.0f, 0.0f), &error));
    CHECK(error.message.find("anchor") != std::string::npos);
    CHECK_FALSE(p.moveAnchor(glm::vec3(1e30f, 0.0f, 0.0f), &error));
    CHECK(p.origin(0) == origin);
    auto same = p.moveAnchor(glm::vec3(1.0f), &error);
    REQUIRE(same);
    for (const LevelUpdate& u : *same) CHECK(u.entered.empty());
    p.invalidate();
    auto all = p.moveAnchor(glm::vec3(1.0f), &error);
    REQUIRE(all);
    for (const LevelUpdate& u : *all) {
        REQUIRE(u.entered.size() == 1);
        CHECK(u.entered[0].voxelCount() == 32u * 32u * 32u);
    }
}

TEST_CASE("the coarsest level's mips fit their slab of the traced volumes without overlapping", "[vct][cpu]") {
    for (uint32_t resolution : {32u, 64u, 128u, 256u})
        for (uint32_t levels : {2u, 8u}) {
            const uint32_t mips = uint32_t(std::log2(double(resolution)));  // the most a description may ask for
            const int slab = int(levels * (resolution + 2));
            std::set<Voxel> used;
            for (uint32_t m = 1; m <= mips; ++m) {
                const glm::ivec3 lo = detail::mipBoxOffset(m, levels, resolution);
                const int size = detail::mipBoxSize(m, resolution);
                INFO(resolution << "³ × " << levels << ", mip " << m << " at " << lo.x << "," << lo.y << "," << lo.z << " size " << size);
                CHECK(size == int(resolution >> m) + 3);
                REQUIRE(glm::all(glm::greaterThanEqual(lo, glm::ivec3(0, 0, slab))));
                REQUIRE(lo.x + size <= int(resolution));
                REQUIRE(lo.y + size <= int(resolution));
                REQUIRE(lo.z + size <= int(detail::tracedSlices(levels, resolution)));
                const std::set<Voxel> box = voxelsOf({lo, lo + glm::ivec3(size)});
                for (const Voxel& v : box) REQUIRE(used.insert(v).second);
            }
        }
}
