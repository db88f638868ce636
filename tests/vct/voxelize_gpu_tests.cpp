// Voxelization through draw records on both backends (vct::Clipmap::voxelizationState): VXGI's emissive test
// cube gives exactly the expected voxels and emittance, no small or thin triangle is lost, scrolling and moving
// objects equal a voxelization from scratch, the two backends agree word for word, bad input is refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "backend_test.h"
#include "test_device.h"
#include "voxelize_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

constexpr uint32_t kResolution = 32;
float axisOpacity(uint32_t word, int axis) { return float((word >> (8 * axis)) & 255u) / 255.0f; }

// 2 levels of 32³ with 1-unit finest voxels; the anchor puts level 0 at world [0, 32)³ and level 1 (2-unit voxels)
// at [−16, 48)³.
vct::ClipmapDesc testDesc(bool persistent = true, vct::EmittanceMode mode = vct::EmittanceMode::Anisotropic) {
    vct::ClipmapDesc d;
    d.levels = 2;
    d.resolution = kResolution;
    d.finestVoxelSize = 1.0f;
    d.persistent = persistent;
    d.emittance = mode;
    return d;
}
const glm::vec3 kAnchor(16.5f, 16.5f, 16.5f);
// The surface voxels only (thickness 0), whose sets the tests state exactly.
vct::VoxelMaterial thinMaterial() {
    vct::VoxelMaterial m;
    m.thickness = 0.0f;
    return m;
}

// The part of [v, v + 1) a face spanning [lo, hi] covers along one axis.
float coverage(int v, float lo, float hi) { return std::max(0.0f, std::min(float(v + 1), hi) - std::max(float(v), lo)); }

void emissiveCubeVoxelizesExactly(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    VoxelizeHarness h(td, testDesc());
    Error error;
    REQUIRE(h.clipmap().update(kAnchor, &error));
    REQUIRE(h.clipmap().placement().origin(0) == glm::ivec3(0));
    REQUIRE(h.clipmap().placement().origin(1) == glm::ivec3(-8));
    h.clipmap().setCountersEnabled(true);
    h.clipmap().resetCounters();
    // The cube inside level 0, faces at half voxels so that no face lies on a voxel boundary; a second one in
    // level 1 only (world [36.5, 43.5] = level-1 voxels [18.25, 21.75]).
    const glm::vec3 lo(4.5f), hi(12.5f), lo1(36.5f), hi1(43.5f);
    const glm::vec3 radiance(1.0f, 0.5f, 0.25f);
    std::vector<Triangle> scene = boxTriangles(lo, hi), cube1 = boxTriangles(lo1, hi1);
    scene.insert(scene.end(), cube1.begin(), cube1.end());
    h.draw(scene, thinMaterial(), &radiance);
    const std::vector<uint32_t> opacity = h.opacity();  // before the downsampling
    h.clipmap().finishVoxelization();
    const std::vector<float> emittance = h.emittance();  // level 0's light: the draws' (finishing downsamples level 1)

    // Level 0: exactly the cube's shell, opaque; everything else empty.
    uint64_t mismatches = 0, shell = 0;
    for (int z = 0; z < 32; ++z)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                const glm::ivec3 v(x, y, z);
                const bool inside = glm::all(glm::greaterThanEqual(v, glm::ivec3(4))) && glm::all(glm::lessThanEqual(v, glm::ivec3(12)));
                const bool onShell = inside && (x == 4 || x == 12 || y == 4 || y == 12 || z == 4 || z == 12);
                shell += onShell;
                const uint32_t got = h.opacityAt(opacity, 0, v);
                // A face blocks light along its normal's axis only.
                const uint32_t expected = inside ? ((x == 4 || x == 12) ? 255u : 0u) | ((y == 4 || y == 12) ? 255u << 8 : 0u) |
                                                       ((z == 4 || z == 12) ? 255u << 16 : 0u)
                                                 : 0u;
                if (got != expected) {
                    if (++mismatches < 8) UNSCOPED_INFO("level 0 voxel " << x << "," << y << "," << z << ": " << got);
                }
                // Emittance per direction: each face sends its light towards its normal from the voxels it makes
                // opaque along it, weighted by that opacity (1: what a cone sees through the voxel's face is the
                // face's radiance wherever in the voxel it lies, however much of the face it covers).
                for (int d = 0; d < 6; ++d) {
                    const int axis = d % 3;
                    const bool positive = d < 3;
                    const int layer = positive ? 12 : 4;
                    float area = 0.0f;
                    if (v[axis] == layer)
                        area = coverage(v[(axis + 1) % 3], lo.x, hi.x) * coverage(v[(axis + 2) % 3], lo.x, hi.x);
                    // These radiances are exact in RGB9E5: no rounding.
                    for (int c = 0; c < 3; ++c) {
                        const float expected = area > 0.0f ? radiance[c] : 0.0f;
                        const float word = emittance[h.wordIndex(0, v, uint32_t(d * 3 + c))];
                        if (word != expected && ++mismatches < 8)
                            UNSCOPED_INFO("level 0 voxel " << x << "," << y << "," << z << " direction " << d << " channel " << c
                                                           << ": " << word << ", expected " << expected);
                    }
                }
            }
    CHECK(shell == 9 * 9 * 9 - 7 * 7 * 7);
    CHECK(mismatches == 0);

    // Level 1 outside level 0: the second cube's shell, written directly. Inside level 0 nothing yet (the
    // downsampling fills it).
    mismatches = 0;
    for (int z = -8; z < 24; ++z)
        for (int y = -8; y < 24; ++y)
            for (int x = -8; x < 24; ++x) {
                const glm::ivec3 v(x, y, z);
                const bool inside = glm::all(glm::greaterThanEqual(v, glm::ivec3(18))) && glm::all(glm::lessThanEqual(v, glm::ivec3(21)));
                const uint32_t expected = inside ? ((x == 18 || x == 21) ? 255u : 0u) | ((y == 18 || y == 21) ? 255u << 8 : 0u) |
                                                       ((z == 18 || z == 21) ? 255u << 16 : 0u)
                                                 : 0u;
                if (h.opacityAt(opacity, 1, v) != expected && ++mismatches < 8)
                    UNSCOPED_INFO("level 1 voxel " << x << "," << y << "," << z << ": " << h.opacityAt(opacity, 1, v));
            }
    CHECK(mismatches == 0);
    const vct::VoxelizationCounters counters = h.clipmap().readCounters();
    CHECK(counters.fragments > 0);
    CHECK(counters.voxelsWritten >= shell);
    CHECK(counters.killedNotDirty == 0);
    CHECK(counters.emittanceWrites > 0);

    // The downsampling: level 1 inside level 0 from its children (complements along each axis, averaged), within
    // one unit of the CPU's arithmetic.
    const std::vector<uint32_t> after = h.opacity();
    mismatches = 0;
    uint64_t filled = 0;
    for (int z = 0; z < 16; ++z)
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                uint32_t children[8];
                for (int i = 0; i < 8; ++i)
                    children[i] = h.opacityAt(opacity, 0, glm::ivec3(x, y, z) * 2 + glm::ivec3(i & 1, (i >> 1) & 1, i >> 2));
                const uint32_t got = h.opacityAt(after, 1, {x, y, z});
                filled += got != 0;
                for (int axis = 0; axis < 3; ++axis) {
                    float expected = 0.0f;
                    for (int i = 0; i < 8; ++i)
                        if (!(i & (1 << axis)))
                            expected += (1.0f - (1.0f - axisOpacity(children[i], axis)) * (1.0f - axisOpacity(children[i + (1 << axis)], axis))) * 0.25f;
                    const int64_t want = std::lround(double(expected) * 255.0), have = (got >> (8 * axis)) & 255u;
                    if (std::abs(have - want) > 1 && ++mismatches < 8)
                        UNSCOPED_INFO("level 1 voxel " << x << "," << y << "," << z << " axis " << axis << ": " << have << ", expected " << want);
                }
            }
    CHECK(filled > 0);
    CHECK(mismatches == 0);
    REQUIRE_NO_MESSAGES(td);
}

// Random triangles far smaller than a voxel, and needles 5 voxels long and 1/1000 wide: every voxel one of
// their points lies in is opaque, and nothing lies further than a voxel from some triangle.
void smallTrianglesAreNotLost(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    VoxelizeHarness h(td, testDesc());
    Error error;
    REQUIRE(h.clipmap().update(kAnchor, &error));
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    auto awayFromBoundaries = [&](float lo, float hi) {  // a coordinate at least 1/100 voxel from an integer
        for (;;) {
            const float x = lo + (hi - lo) * unit(rng);
            const float f = x - std::floor(x);
            if (f > 0.01f && f < 0.99f) return x;
        }
    };
    std::vector<Triangle> triangles;
    std::vector<glm::vec3> mustBeOpaque;
    for (int i = 0; i < 300; ++i) {
        const glm::vec3 c(awayFromBoundaries(3, 29), awayFromBoundaries(3, 29), awayFromBoundaries(3, 29));
        const float size = 0.01f + 0.4f * unit(rng);
        Triangle t;
        for (glm::vec3& p : t.p)
            p = c + size * glm::vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f);
        t.normal = glm::vec3(0, 0, 1);
        bool clean = true;  // keep the vertices themselves off voxel boundaries
        for (const glm::vec3& p : t.p)
            for (int a = 0; a < 3; ++a) {
                const float f = p[a] - std::floor(p[a]);
                clean = clean && f > 0.01f && f < 0.99f;
            }
        if (!clean) continue;
        triangles.push_back(t);
        for (const glm::vec3& p : t.p) mustBeOpaque.push_back(p);
    }
    for (int i = 0; i < 40; ++i) {
        const glm::vec3 a(awayFromBoundaries(6, 26), awayFromBoundaries(6, 26), awayFromBoundaries(6, 26));
        glm::vec3 dir = glm::normalize(glm::vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f));
        const glm::vec3 b = a + 5.0f * dir;
        const glm::vec3 side = 0.001f * glm::normalize(glm::cross(dir, glm::vec3(0.3f, 0.7f, 0.2f)));
        triangles.push_back({{a, b, a + side}, glm::vec3(0, 0, 1)});
        for (int s = 0; s <= 100; ++s) {
            const glm::vec3 p = a + (b - a) * (float(s) / 100.0f);
            bool clean = true;
            for (int ax = 0; ax < 3; ++ax) {
                const float f = p[ax] - std::floor(p[ax]);
                clean = clean && f > 0.01f && f < 0.99f;
            }
            if (clean) mustBeOpaque.push_back(p);
        }
    }
    h.draw(triangles, thinMaterial(), nullptr);
    const std::vector<uint32_t> opacity = h.opacity();
    uint64_t lost = 0;
    for (const glm::vec3& p : mustBeOpaque)
        if (h.opacityAt(opacity, 0, glm::ivec3(glm::floor(p))) == 0u && ++lost < 8) UNSCOPED_INFO("lost the point " << p.x << "," << p.y << "," << p.z);
    CHECK(lost == 0);
    uint64_t stray = 0, set = 0;
    for (int z = 0; z < 32; ++z)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                if (!h.opacityAt(opacity, 0, {x, y, z})) continue;
                ++set;
                bool near = false;
                for (const Triangle& t : triangles) {
                    const glm::vec3 lo = glm::min(glm::min(t.p[0], t.p[1]), t.p[2]) - 1.0f, hi = glm::max(glm::max(t.p[0], t.p[1]), t.p[2]) + 1.0f;
                    near = near || (x + 1 > lo.x && x < hi.x && y + 1 > lo.y && y < hi.y && z + 1 > lo.z && z < hi.z);
                }
                stray += !near;
            }
    INFO(set << " opaque voxels for " << triangles.size() << " triangles");
    CHECK(stray == 0);
    CHECK(set < 4 * mustBeOpaque.size());
    REQUIRE_NO_MESSAGES(td);
}

// A scene over both levels: the cube, a wall, random triangles.
std::vector<Triangle> sceneAt(const glm::vec3& offset) {
    std::vector<Triangle> s = boxTriangles(glm::vec3(4.5f) + offset, glm::vec3(12.5f) + offset);
    std::vector<Triangle> wall = boxTriangles(glm::vec3(-10.3f, 2.2f, 1.7f), glm::vec3(44.6f, 3.1f, 30.2f));
    s.insert(s.end(), wall.begin(), wall.end());
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> pos(-15.0f, 47.0f), small(-1.5f, 1.5f);
    for (int i = 0; i < 200; ++i) {
        const glm::vec3 c(pos(rng), pos(rng), pos(rng));
        Triangle t;
        for (glm::vec3& p : t.p) p = c + glm::vec3(small(rng), small(rng), small(rng));
        t.normal = glm::normalize(glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]));
        s.push_back(t);
    }
    return s;
}

// Opacity word for word (a maximum: the order of writes does not matter); light the same (integer sums, canonical
// RGB9E5: kLightDifferenceBound is none).
void expectSameVoxels(VoxelizeHarness& a, VoxelizeHarness& b) {
    const std::vector<uint32_t> oa = a.opacity(), ob = b.opacity();
    const std::vector<float> ea = a.emittance(), eb = b.emittance();
    const vct::ClipmapPlacement& p = a.clipmap().placement();
    REQUIRE(p.origin(0) == b.clipmap().placement().origin(0));
    REQUIRE(p.origin(1) == b.clipmap().placement().origin(1));
    uint64_t differ = 0, opaque = 0;
    for (size_t t = 0; t < oa.size(); ++t) {
        opaque += oa[t] != 0;
        if (oa[t] != ob[t] && ++differ < 8) UNSCOPED_INFO("texel " << t << ": opacity " << oa[t] << " vs " << ob[t]);
    }
    CHECK(differ == 0);
    CHECK(opaque > 1000);
    size_t where = 0;
    const size_t lightDiffers = radianceDifferences(ea, eb, oa.size(), kLightDifferenceBound, &where);
    INFO("first differing channel " << where << ": " << (lightDiffers ? ea[where] : 0.0f) << " vs " << (lightDiffers ? eb[where] : 0.0f));
    CHECK(lightDiffers == 0);
    float lit = 0.0f;
    for (float v : ea) lit += v;
    CHECK(lit > 0.0f);
}

// Persistent voxels: scroll the anchor (both levels move) and move an object; the volumes then equal a fresh
// clip-map voxelized at the new anchor with the object where it now is.
void scrollingEqualsFromScratch(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const glm::vec3 radiance(0.8f, 0.6f, 0.4f);
    const glm::vec3 moved(3.0f, -2.0f, 1.0f);
    VoxelizeHarness scrolled(td, testDesc());
    Error error;
    REQUIRE(scrolled.clipmap().update(kAnchor, &error));
    scrolled.draw(sceneAt(glm::vec3(0.0f)), thinMaterial(), &radiance);
    scrolled.clipmap().finishVoxelization();
    const glm::vec3 anchor2 = kAnchor + glm::vec3(5.2f, -3.9f, 2.1f);
    // The cube moves: invalidate where it was and where it is.
    const std::vector<vct::WorldBox> invalidated{{glm::vec3(4.5f), glm::vec3(12.5f)}, {glm::vec3(4.5f) + moved, glm::vec3(12.5f) + moved}};
    auto updates = scrolled.clipmap().update(anchor2, &error, invalidated);
    REQUIRE(updates);
    REQUIRE((*updates)[1].origin != glm::ivec3(-8));  // level 1 moved too
    scrolled.draw(sceneAt(moved), thinMaterial(), &radiance);
    scrolled.clipmap().finishVoxelization();

    VoxelizeHarness fresh(td, testDesc());
    REQUIRE(fresh.clipmap().update(anchor2, &error));
    fresh.draw(sceneAt(moved), thinMaterial(), &radiance);
    fresh.clipmap().finishVoxelization();
    expectSameVoxels(scrolled, fresh);
    REQUIRE_NO_MESSAGES(td);
}

void refusesBadInput(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    VoxelizeHarness h(td, testDesc());
    Error error;
    vct::VoxelMaterial bad;
    bad.thickness = NAN;  // 
    CHECK_FALSE(h.clipmap().voxelizationState(bad, &error));
    CHECK(error.message.find("thickness") != std::string::npos);
    bad = {};
    bad.opacity = 1.5f;
    CHECK_FALSE(h.clipmap().voxelizationState(bad, &error));
    CHECK(error.message.find("opacity") != std::string::npos);
    REQUIRE(h.clipmap().update(kAnchor, &error));
    // A non-finite invalidated box: refused, nothing moves.
    CHECK_FALSE(h.clipmap().update(kAnchor + glm::vec3(8.0f), &error, {{glm::vec3(0.0f), glm::vec3(INFINITY)}}));
    CHECK(error.message.find("invalidated box 0") != std::string::npos);
    CHECK(h.clipmap().placement().origin(0) == glm::ivec3(0));
    // Triangles with NaN or huge vertices are dropped; the good one next to them is voxelized alone.
    std::vector<Triangle> triangles = boxTriangles(glm::vec3(4.5f), glm::vec3(5.5f));
    triangles.push_back({{glm::vec3(NAN), glm::vec3(1.0f), glm::vec3(2.0f, 1.0f, 1.0f)}, glm::vec3(0, 0, 1)});
    triangles.push_back({{glm::vec3(1e30f), glm::vec3(1.0f), glm::vec3(2.0f, 1.0f, 1.0f)}, glm::vec3(0, 0, 1)});
    triangles.push_back({{glm::vec3(20.5f), glm::vec3(20.5f), glm::vec3(20.5f)}, glm::vec3(0, 0, 1)});  // degenerate
    const glm::vec3 radiance(NAN, -1.0f, 2.0f);  // NaN and negative light add nothing
    h.draw(triangles, thinMaterial(), &radiance);
    h.clipmap().finishVoxelization();
    const std::vector<uint32_t> opacity = h.opacity();
    uint64_t set = 0;
    for (int z = 0; z < 32; ++z)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) set += h.opacityAt(opacity, 0, {x, y, z}) != 0;
    CHECK(set == 8);  // the unit cube at [4.5, 5.5]³ touches 2³ voxels
    const std::vector<float> emittance = h.emittance();
    CHECK(emittance[h.wordIndex(0, {5, 5, 5}, 0)] == 0.0f);  // +X, red (NaN)
    CHECK(emittance[h.wordIndex(0, {5, 5, 5}, 1)] == 0.0f);  // +X, green (negative)
    // A quarter of the +X face, which the voxel's opacity along x (1) counts whole: blue 2 (exact in RGB9E5).
    CHECK(emittance[h.wordIndex(0, {5, 5, 5}, 2)] == 2.0f);
    REQUIRE_NO_MESSAGES(td);
}

// The emittance function is called with the fragment's point on the triangle, its normal and its level.
void hookSeesTheFragment(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    VoxelizeHarness h(td, testDesc());
    Error error;
    REQUIRE(h.clipmap().update(kAnchor, &error));
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("vct_tests/voxelize_position.frag");
    REQUIRE(sd.blob);
    vct::VoxelMaterial m = thinMaterial();
    m.fragmentShader = td.device->createShader(sd);
    REQUIRE(m.fragmentShader);
    // A square at z = 10.25 over x, y in [4.25, 5.75]: 3 × 3 of the 4 × 4 samples of each of 2 × 2 pixels.
    const glm::vec3 a(4.25f, 4.25f, 10.25f), b(5.75f, 4.25f, 10.25f), c(5.75f, 5.75f, 10.25f), d(4.25f, 5.75f, 10.25f);
    const glm::vec3 up(0.0f, 0.0f, 1.0f), unused(1.0f);
    h.draw({{{a, b, c}, up}, {{a, c, d}, up}}, m, &unused);
    h.clipmap().finishVoxelization();
    const std::vector<float> emittance = h.emittance();
    for (int y = 4; y <= 5; ++y)
        for (int x = 4; x <= 5; ++x) {
            // The hook's light as the voxel sends it through its +Z face: its radiance (the mean over the samples of
            // the voxel's face inside the square, 9 of 16, all at the same point) times the voxel's opacity along z, 1.
            auto word = [&](uint32_t c) { return emittance[h.wordIndex(0, {x, y, 10}, 2 * 3 + c)]; };  // +Z
            const glm::vec3 seen{word(0), word(1), word(2)};
            INFO("voxel " << x << "," << y << ": the hook saw " << seen.x << "," << seen.y << "," << seen.z);
            // RGB9E5 keeps 9 bits of the largest channel (z = 10.25): half a unit is 2^-6.
            const float margin = 10.25f / 512.0f;
            CHECK(seen.x == Approx(x + 0.5f).margin(margin));
            CHECK(seen.y == Approx(y + 0.5f).margin(margin));
            CHECK(seen.z == Approx(10.25f).margin(margin));
        }
    td.device->destroy(m.fragmentShader);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("voxelization hands the emittance function the fragment's position", "[vct]", hookSeesTheFragment)
BACKEND_TEST("voxelization of the emissive test cube gives exactly the expected voxels", "[vct][quick]", emissiveCubeVoxelizesExactly)
BACKEND_TEST("voxelization loses no small or thin triangle", "[vct]", smallTrianglesAreNotLost)
BACKEND_TEST("voxelization after scrolling and a moved object equals one from scratch", "[vct]", scrollingEqualsFromScratch)
BACKEND_TEST("voxelization refuses bad materials and boxes and drops bad triangles", "[vct]", refusesBadInput)

#if defined(BRICKLIGHT_HAS_VULKAN) && defined(BRICKLIGHT_HAS_GL)
TEST_CASE("voxelization: Vulkan and GL write the same voxels", "[vct][cross]") {
    TestDevice vk = makeDevice("vulkan"), gl = makeDevice("gl");
    REQUIRE(vk.device);
    REQUIRE(gl.device);
    const glm::vec3 radiance(0.7f, 0.3f, 1.9f);
    VoxelizeHarness a(vk, testDesc()), b(gl, testDesc());
    Error error;
    for (VoxelizeHarness* h : {&a, &b}) {
        REQUIRE(h->clipmap().update(kAnchor, &error));
        h->draw(sceneAt(glm::vec3(0.5f, 0.25f, -0.75f)), vct::VoxelMaterial{0.5f, true, 0.8f, {}}, &radiance);
        h->clipmap().finishVoxelization();
    }
    expectSameVoxels(a, b);
    REQUIRE_NO_MESSAGES(vk);
    REQUIRE_NO_MESSAGES(gl);
}
#endif
