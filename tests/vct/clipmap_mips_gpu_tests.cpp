// The coarsest level's mips on both backends: each mip holds the one below it (or the level) downsampled as
// downsample.comp combines voxels — checked texel by texel against the same rule on the CPU, with an empty border,
// also after the level scrolled — and cones wider than the coarsest voxels read them: a pattern finer than a wide
// cone's samples gives the same light wherever they fall.
#include <catch2/catch.hpp>

#include <cmath>

#include "backend_test.h"
#include "../../core/vct/clipmap_regions.h"
#include "test_device.h"
#include "voxelize_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

// The atlas read back as floats (bricklight/vct_layout.glsl), region by region without the border columns: opacity
// (rgb) and the emittance regions (RGB9E5 words, rgb each).
struct Traced {
    uint32_t width = 0, height = 0, depth = 0;
    std::vector<glm::vec4> opacity;
    std::vector<std::vector<glm::vec4>> emittance;
    size_t index(glm::ivec3 t) const { return (size_t(t.z) * height + size_t(t.y)) * width + size_t(t.x); }
};

Traced readTraced(TestDevice& td, vct::Clipmap& clipmap, uint32_t volumes) {
    Traced t;
    const rhi::TextureDesc* d = td.device->describe(clipmap.atlas());
    REQUIRE(d);
    const uint32_t r = clipmap.desc().resolution;
    t.width = r;
    t.height = d->height;
    t.depth = d->depthOrLayers;
    std::vector<uint32_t> atlas(size_t(d->width) * d->height * d->depthOrLayers);
    REQUIRE(td.device->readTexture(clipmap.atlas(), {}, atlas.data()));
    auto region = [&](uint32_t index) {
        std::vector<uint32_t> words;
        for (uint32_t z = 0; z < t.depth; ++z)
            for (uint32_t y = 0; y < t.height; ++y)
                for (uint32_t x = 0; x < t.width; ++x) words.push_back(atlas[(size_t(z) * d->height + y) * d->width + index * (r + 2) + 1 + x]);
        return words;
    };
    for (uint32_t w : region(0)) t.opacity.push_back(glm::vec4(float(w & 255u), float((w >> 8) & 255u), float((w >> 16) & 255u), 0.0f) / 255.0f);
    for (uint32_t v = 0; v < volumes; ++v) {
        std::vector<glm::vec4> values;
        for (uint32_t w : region(1 + v)) values.push_back(glm::vec4(decodeRgb9e5(w), 0.0f));
        t.emittance.push_back(std::move(values));
    }
    return t;
}

// Checks every texel of mip m against its children in the level or mip below, as read back.
void checkMip(const vct::Clipmap& clipmap, const Traced& t, uint32_t m, size_t* nonEmpty) {
    const vct::ClipmapDesc& d = clipmap.desc();
    const uint32_t coarsest = d.levels - 1, r = d.resolution;
    const glm::ivec3 origin = clipmap.placement().origin(coarsest);
    const glm::ivec3 box = vct::detail::mipBoxOffset(m, d.levels, r), lo = (origin >> int(m)) - 1;
    const int size = vct::detail::mipBoxSize(m, r);
    // The stored texel of a child (a world voxel of the level or mip below), or none outside its region.
    auto child = [&](glm::ivec3 c, glm::ivec3* texel) {
        if (m == 1) {
            if (!clipmap.placement().contains(coarsest, c)) return false;
            const glm::ivec3 w = clipmap.placement().toroidalTexel(c);
            *texel = glm::ivec3(w.x, w.y, int(coarsest * (r + 2) + 1) + w.z);
            return true;
        }
        const glm::ivec3 below = (origin >> int(m - 1)) - 1, rel = c - below;
        const int width = vct::detail::mipBoxSize(m - 1, r);
        if (glm::any(glm::lessThan(rel, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(rel, glm::ivec3(width)))) return false;
        *texel = vct::detail::mipBoxOffset(m - 1, d.levels, r) + rel;
        return true;
    };
    const bool anisotropic = d.emittance == vct::EmittanceMode::Anisotropic, isotropic = d.emittance == vct::EmittanceMode::Isotropic;
    size_t mismatches = 0;
    for (int z = 0; z < size; ++z)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::ivec3 voxel = lo + glm::ivec3(x, y, z);
                glm::vec3 alpha[8];
                glm::ivec3 texel[8];
                bool valid[8];
                for (int i = 0; i < 8; ++i) {
                    valid[i] = child(voxel * 2 + glm::ivec3(i & 1, (i >> 1) & 1, i >> 2), &texel[i]);
                    alpha[i] = valid[i] ? glm::vec3(t.opacity[t.index(texel[i])]) : glm::vec3(0.0f);
                }
                glm::vec3 opacity(0.0f), mean(0.0f);
                glm::vec3 directional[6];
                for (int axis = 0; axis < 3; ++axis)
                    for (int j = 0; j < 4; ++j) {
                        const int lower = axis == 0 ? 2 * j : (axis == 1 ? (j & 1) + 4 * (j >> 1) : j), upper = lower + (1 << axis);
                        opacity[axis] += (1.0f - (1.0f - alpha[lower][axis]) * (1.0f - alpha[upper][axis])) * 0.25f;
                        for (int side = 0; side < 2; ++side) {
                            const int dir = axis + 3 * side, nearChild = side == 0 ? upper : lower, farChild = side == 0 ? lower : upper;
                            if (j == 0) directional[dir] = glm::vec3(0.0f);
                            if (!isotropic && !anisotropic) continue;
                            const std::vector<glm::vec4>& e = t.emittance[anisotropic ? dir : 0];
                            const glm::vec3 nearE = valid[nearChild] ? glm::vec3(e[t.index(texel[nearChild])]) : glm::vec3(0.0f);
                            const glm::vec3 farE = valid[farChild] ? glm::vec3(e[t.index(texel[farChild])]) : glm::vec3(0.0f);
                            directional[dir] += 0.25f * (nearE + (1.0f - alpha[nearChild][axis]) * farE);
                        }
                    }
                for (const glm::vec3& v : directional) mean += v / 6.0f;
                const size_t at = t.index(box + glm::ivec3(x, y, z));
                bool same = glm::all(glm::lessThanEqual(glm::abs(glm::vec3(t.opacity[at]) - opacity), glm::vec3(1.0f / 255.0f)));
                // RGB9E5 storage rounds each channel to 2^-10 of the texel's largest one; the expectation is computed
                // from the children as stored.
                auto close = [](glm::vec3 a, glm::vec3 b) {
                    const float largest = std::max(b.x, std::max(b.y, b.z));
                    return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(2.0e-3f * largest + 1.0e-6f)));
                };
                if (isotropic) same = same && close(glm::vec3(t.emittance[0][at]), mean);
                if (anisotropic)
                    for (int dir = 0; dir < 6; ++dir)
                        same = same && close(glm::vec3(t.emittance[size_t(dir)][at]), directional[dir]);
                const bool border = x == 0 || y == 0 || z == 0 || x == size - 1 || y == size - 1 || z == size - 1;
                if (border) same = same && t.opacity[at] == glm::vec4(0.0f);
                if (!same && mismatches++ < 5)
                    UNSCOPED_INFO("mip " << m << " texel " << x << "," << y << "," << z << ": opacity " << t.opacity[at].x << "," << t.opacity[at].y
                                         << "," << t.opacity[at].z << " expected " << opacity.x << "," << opacity.y << "," << opacity.z);
                *nonEmpty += opacity != glm::vec3(0.0f);
            }
    CHECK(mismatches == 0);
}

void mipsHoldTheLevelDownsampled(const std::string& backend, vct::EmittanceMode mode) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    vct::ClipmapDesc desc = testClipmapDesc(2, mode);
    VoxelizeHarness h(td, desc);
    REQUIRE(vct::clipmapMipLevels(desc) == 3);
    // Boxes of several sizes across the coarsest level (64 units wide), some near its edges.
    auto draw = [&]() {
        const glm::vec3 red(1.0f, 0.2f, 0.1f), blue(0.1f, 0.3f, 2.0f);
        h.draw(boxTriangles(glm::vec3(-13.0f, -9.0f, -11.0f), glm::vec3(-5.0f, 3.0f, 1.0f)), vct::VoxelMaterial{}, &red);
        h.draw(boxTriangles(glm::vec3(30.0f, 8.0f, 20.0f), glm::vec3(47.0f, 12.5f, 43.0f)), vct::VoxelMaterial{}, &blue);
        h.draw(boxTriangles(glm::vec3(4.5f), glm::vec3(7.5f)), vct::VoxelMaterial{}, &red);
    };
    Error error;
    // An anchor whose coarsest origin is not a multiple of the mips' voxels: their edge voxels reach past it.
    REQUIRE(h.clipmap().update(glm::vec3(16.5f, 18.3f, 14.9f), &error));
    draw();
    h.clipmap().finishVoxelization();
    const uint32_t volumes = mode == vct::EmittanceMode::Anisotropic ? 6 : mode == vct::EmittanceMode::Isotropic ? 1 : 0;
    for (int round = 0; round < 2; ++round) {
        INFO("round " << round << ": coarsest origin " << h.clipmap().placement().origin(1).x << "," << h.clipmap().placement().origin(1).y << ","
                      << h.clipmap().placement().origin(1).z);
        const glm::ivec3 o = h.clipmap().placement().origin(1);
        CHECK(((o.x | o.y | o.z) & 7) != 0);  // not aligned to mip 3's voxels
        const Traced t = readTraced(td, h.clipmap(), volumes);
        size_t nonEmpty[4] = {};
        for (uint32_t m = 1; m <= 3; ++m) checkMip(h.clipmap(), t, m, &nonEmpty[m]);
        CHECK(nonEmpty[1] > 20);
        CHECK(nonEmpty[3] > 2);
        // Scroll the coarsest level by some of its voxels: the mips follow it.
        REQUIRE(h.clipmap().update(glm::vec3(27.2f, 5.1f, 20.0f), &error));
        draw();
        h.clipmap().finishVoxelization();
    }
    REQUIRE_NO_MESSAGES(td);
}

// A wide cone towards a slab of small emissive cubes (2 units, every 4): its samples are wider than the coarsest
// voxels (2 units) for most of the way, so it reads the mips; the light it gathers must not depend on where its
// samples fall relative to the pattern. Point-sampling the coarsest level instead would see the cubes or the gaps.
void wideConesReadTheMips(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    vct::ClipmapDesc desc = testClipmapDesc(2);
    VoxelizeHarness h(td, desc);
    Error error;
    REQUIRE(h.clipmap().update(glm::vec3(16.5f), &error));
    std::vector<Triangle> cubes;
    // The cone runs along the clip-map's middle: a sample as wide as the mips' voxels needs half its width of
    // the coarsest level (world −16..48) around it.
    for (int y = -6; y < 38; y += 4)
        for (int z = -6; z < 38; z += 4)
            for (int x = 14; x < 26; x += 4) {
                const std::vector<Triangle> c = boxTriangles(glm::vec3(float(x), float(y), float(z)), glm::vec3(float(x + 2), float(y + 2), float(z + 2)));
                cubes.insert(cubes.end(), c.begin(), c.end());
            }
    const glm::vec3 one(1.0f);
    vct::VoxelMaterial thin;
    thin.thickness = 0.0f;
    h.draw(cubes, thin, &one);
    h.clipmap().finishVoxelization();

    std::vector<ConeIn> cones;
    for (int sy = 0; sy < 4; ++sy)
        for (int sz = 0; sz < 4; ++sz) cones.push_back({glm::vec4(-10.0f, 14.0f + float(sy), 14.0f + float(sz), 1.2f), glm::vec4(1.0f, 0.0f, 0.0f, 0.0f)});
    const std::vector<ConeOut> results = traceCones(td, h, cones);
    float lo = 1e30f, hi = 0.0f, sum = 0.0f;
    for (size_t i = 0; i < cones.size(); ++i) {
        const float light = results[i].radiance.x;
        lo = std::min(lo, light);
        hi = std::max(hi, light);
        sum += light;
    }
    const float mean = sum / float(cones.size());
    // Measured: every cone 0.219 with the mips; without them (the cone point-sampling the coarsest level) 0 to
    // 0.078, mean 0.020.
    INFO("light: min " << lo << " max " << hi << " mean " << mean);
    CHECK(mean > 0.05f);
    CHECK((hi - lo) / mean < 0.15f);
    REQUIRE_NO_MESSAGES(td);
}

void mipsAnisotropic(const std::string& backend) { mipsHoldTheLevelDownsampled(backend, vct::EmittanceMode::Anisotropic); }
void mipsIsotropic(const std::string& backend) { mipsHoldTheLevelDownsampled(backend, vct::EmittanceMode::Isotropic); }
void mipsOpacityOnly(const std::string& backend) { mipsHoldTheLevelDownsampled(backend, vct::EmittanceMode::None); }

}  // namespace

BACKEND_TEST("the coarsest level's mips hold it downsampled (anisotropic)", "[vct]", mipsAnisotropic)
BACKEND_TEST("the coarsest level's mips hold it downsampled (isotropic)", "[vct]", mipsIsotropic)
BACKEND_TEST("the coarsest level's mips hold it downsampled (opacity only)", "[vct]", mipsOpacityOnly)
BACKEND_TEST("cones wider than the coarsest voxels read its mips", "[vct]", wideConesReadTheMips)
