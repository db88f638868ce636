// The "foliage" built-in scene and generated textures: the scene holds its alpha-tested grass and leaf cards
// with generated textures; rendered, the path tracer and the G-buffer agree on which pixels are foliage (both
// leave the cut-out texels out) and the ground shows between the grass blades. Generated textures need no
// image library and a malformed one is refused naming its mesh. The SDF GI with alpha-aware cards against the
// naive variants and the path tracer.
#include <algorithm>
#include <cmath>

#include "backend_test.h"
#include "foliage_test_support.h"
#include "image_metrics.h"
#include "path_tracer.h"
#include "raster_renderer.h"
#include "shared_references.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

const scenes::TriangleMesh* meshNamed(const scenes::SceneGeometry& s, const std::string& name) {
    for (const scenes::TriangleMesh& m : s.meshes)
        if (m.name == name) return &m;
    return nullptr;
}

// The share of a generated texture's texels whose alpha passes a cut-off of 0.5.
double coverage(const scenes::GeneratedTexture& t) {
    size_t covered = 0;
    for (size_t i = 3; i < t.rgba.size(); i += 4) covered += t.rgba[i] >= 128;
    return double(covered) / double(t.width * t.height);
}

// The foliage scene at 64 x 64, pixel centres: the G-buffer's and the path tracer's primary-hit albedo.
void foliageRenders(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry s = scenes::foliage();
    constexpr uint32_t kSize = 64;
    Pair both = makePair(td, s, kSize, 1, 2, false);
    const render::Image traced = both.tracer->read(render::Aov::Albedo), rastered = both.raster->read(render::Aov::Albedo);
    const render::Image combined = both.tracer->read(render::Aov::Combined);
    REQUIRE(traced.width == kSize);
    CHECK(allFinite(combined.rgb));
    const double mean = imageMean(combined);
    INFO("path-traced mean radiance " << mean);
    CHECK(mean > 0.05);
    CHECK(mean < 5.0);
    size_t disagree = 0, foliage = 0, lowFoliage = 0, lowOther = 0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const bool t = isFoliage(traced.at(x, y)), r = isFoliage(rastered.at(x, y));
            disagree += t != r;
            foliage += t;
            // The bottom quarter of the view is the meadow in front of the camera.
            if (y >= kSize * 3 / 4) (t ? lowFoliage : lowOther)++;
        }
    const double pixels = double(kSize * kSize), low = double(kSize * kSize / 4);
    INFO("foliage pixels: path tracer " << foliage / pixels << ", disagreeing with the G-buffer " << disagree / pixels
                                        << "; in the meadow: foliage " << lowFoliage / low << ", ground between " << lowOther / low);
    // The same cut-out texels in both; the texture coordinates are interpolated differently (the rasterizer's
    // perspective interpolation vs barycentrics), which moves a few blade edges by a texel: 2 % of the pixels.
    CHECK(disagree <= size_t(0.02 * pixels));
    CHECK(foliage > size_t(0.2 * pixels));
    CHECK(foliage < size_t(0.9 * pixels));
    // The grass is dense but has gaps: the ground shows between the blades, and the blades are seen.
    CHECK(lowFoliage > size_t(0.3 * low));
    CHECK(lowOther > size_t(0.05 * low));
    REQUIRE_NO_MESSAGES(td);
}

// A mesh with a generated texture of the wrong byte count, or with both a file and generated texels, is refused.
void badGeneratedTextures(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    scenes::SceneGeometry s = furnace(groundPlane(1.0f, glm::vec3(0.5f)));
    s.camera = {glm::vec3(0, 3, 0), glm::vec3(0), glm::vec3(0, 0, -1), 30.0f};  // looking down at the plane
    s.meshes[0].name = "sheet";
    s.meshes[0].uvs = {0, 0, 1, 0, 1, 1, 0, 1};
    auto texture = std::make_shared<scenes::GeneratedTexture>();
    texture->name = "checks";
    texture->width = 4;
    texture->height = 4;
    texture->rgba.assign(4 * 4 * 4 - 1, 255);
    s.meshes[0].generatedTexture = texture;
    render::PathTracerOptions o;
    o.width = o.height = 8;
    std::string error;
    CHECK(!render::PathTracer::create(*td.device, s, o, &error));
    INFO(error);
    CHECK(error.find("mesh 'sheet'") != std::string::npos);
    CHECK(error.find("generated texture 'checks' is 4 x 4 with 63 bytes") != std::string::npos);
    texture->rgba.push_back(255);
    s.meshes[0].baseColorTexture = "leaf.png";
    CHECK(!render::PathTracer::create(*td.device, s, o, &error));
    CHECK(error.find("mesh 'sheet': has both a base colour texture file ('leaf.png') and a generated texture ('checks')") != std::string::npos);
    // Valid: a 4 x 4 texture resampled to the layer size; the plane's albedo is 0.5 x the texel (sRGB 255: 1).
    s.meshes[0].baseColorTexture.clear();
    auto pt = render::PathTracer::create(*td.device, s, o, &error);
    INFO(error);
    REQUIRE(pt);
    pt->addSamples(1);
    CHECK(std::fabs(pt->read(render::Aov::Albedo).at(4, 4).x - 0.5f) < 0.01f);
    REQUIRE_NO_MESSAGES(td);
}

// The SDF GI's three ways with the cards (RasterOptions::foliage) against the path tracer's indirect diffuse, over
// the whole image and over the grass pixels (the meadow's foliage pixels in the bottom quarter), with the sun behind
// the camera and behind the cards. Figures are printed (WARN) for docs/gi.md, "Foliage".
void giFoliageVariants(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    constexpr uint32_t kSize = 64, kFrames = 16;  // the reference: 64², 256 spp (shared_references.cpp)
    for (bool backLit : {false, true}) {
        const scenes::SceneGeometry s = foliageScene(backLit);
        auto reference = foliageReference(td, backLit);
        size_t grassPixels = 0;
        const std::vector<uint8_t> grass = grassMask(reference.read(render::Aov::Albedo), &grassPixels);
        REQUIRE(grassPixels > kSize * kSize / 8);
        render::RasterOptions o;
        o.width = o.height = kSize;
        o.gi = true;
        FoliageFigures f[3];
        foliageVariants(td, s, o, kFrames, reference.read(render::Aov::IndirectDiffuse), grass, backLit ? 0u : 3u, 8,
                        backend + (backLit ? ", sun behind the cards" : ", sun behind the camera"), f);
        // What holds (measured at 64², 16 frames, 256 spp; both backends alike): with the sun behind the camera the
        // alpha-aware cards beat the solid ones on both numbers, whole and grass (relMSE 0.099 against 0.191, grass
        // 0.178 against 0.373; means 1.86x and 2.22x the reference's) and lose to the cards left out (0.044, grass
        // 0.046, mean 1.40x). With the sun behind the cards they beat both (relMSE 0.0155 against 0.0190 and 0.037,
        // grass 0.021 against 0.026 and 0.057; mean 0.87 against 0.81 and 0.51). After 32 frames (docs/gi.md,
        // "Foliage") the sun-behind-the-camera figures are the same to 0.01 (the solid cards drift up to 0.229, grass
        // 0.415) and with the sun behind the cards the alpha-aware mean reaches 1.00 (the card sides are relit every
        // 8th frame); every check below holds at both. With the alpha cache ignored (the defect these checks guard) the
        // alpha-aware cards are the solid ones, and the first ratio is 1. The target, better than both naive
        // variants in both lights, is not met: a card is thinner than a cache texel and its sides are not resolved
        // (the GI is 2.5x too bright with every card solid in both renderers).
        if (!backLit) {
            CHECK(f[0].whole.relMse < 0.8 * f[1].whole.relMse);
            CHECK(f[0].grass.relMse < 0.8 * f[1].grass.relMse);
            CHECK(meanError(f[0].whole) < meanError(f[1].whole));
            CHECK(meanError(f[0].grass) < meanError(f[1].grass));
            // Converged grass does not flicker: the continued rays' draws are averaged by the GI's history.
            CHECK(f[0].flicker < 0.05);
        } else {
            // The whole image against the solid cards keeps 5 % rather than 10 %: the alpha-aware figure varies from run
            // to run (0.0155-0.0177 on one build, GI's passes race; docs/gi.md, "Races") while the solid cards' stay
            // at 0.0183-0.0193, so a 10 % margin failed on a run of an unchanged build (0.0177 against 0.9 x 0.0191).
            // The defect still fails it: with the alpha cache ignored the ratio is 1.
            for (int naive = 1; naive < 3; ++naive) {
                CHECK(f[0].whole.relMse < (naive == 1 ? 0.95 : 0.9) * f[naive].whole.relMse);
                CHECK(f[0].grass.relMse < 0.9 * f[naive].grass.relMse);
                CHECK(meanError(f[0].whole) < meanError(f[naive].whole));
            }
            CHECK(meanError(f[0].grass) < meanError(f[2].grass));
        }
    }
    REQUIRE_NO_MESSAGES(td);
}

// The alpha pass runs after the frame's field update and before the GI's dispatch, which forgets the cells of
// bricks the update reallocated: it must keep what that frame's pass wrote for them. After the first frame (every
// brick new) the flagged bricks hold counts, as many cells as after a second frame.
void alphaCellsOfNewBricks(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    render::RasterOptions o;
    o.width = o.height = 64;
    o.gi = true;
    std::string error;
    auto r = render::RasterRenderer::create(*td.device, scenes::foliage(), o, &error);
    INFO(error);
    REQUIRE(r);
    auto cellsWithCounts = [&] {
        size_t n = 0;
        for (float c : r->giContext()->readAlphaCoverage()) n += c >= 0.0f;
        return n;
    };
    frames(td, *r, 1);
    const size_t first = cellsWithCounts();
    frames(td, *r, 1);
    const size_t second = cellsWithCounts();
    INFO("cells with counts after the first frame " << first << ", after the second " << second);
    CHECK(second > 1000u);
    CHECK(first >= second * 9 / 10);  // (before the fix: none after the first frame)
    REQUIRE_NO_MESSAGES(td);
}

// Rays that reach the GI's bound on cards passed are counted (gi::GiContext::raysAtAlphaBound): a floor under a
// stack of horizontal cards that are cut out everywhere (coverage 0: every ray passes every card it may). Under 12
// of them the floor's probe rays to the sky meet the bound; under 3, only rays that meet one card's shell again and
// again (a grazing ray's step past a card is at most 3 brixels long): measured 102 and 365 on both backends.
scenes::SceneGeometry floorUnderCards(uint32_t cards) {
    scenes::SceneGeometry s;
    s.meshes.push_back(groundPlane(2.0f, glm::vec3(0.6f)));
    scenes::TriangleMesh stack;
    stack.name = "cards";
    stack.albedo = glm::vec3(0.3f, 0.6f, 0.2f);
    stack.alphaCutoff = 0.5f;
    stack.baseAlpha = 0.25f;  // below the cut-off: cut out everywhere
    for (uint32_t c = 0; c < cards; ++c) {
        const float y = 0.1f + 0.08f * float(c);
        const uint32_t base = uint32_t(stack.positions.size() / 3);
        stack.positions.insert(stack.positions.end(), {-2, y, -2, 2, y, -2, 2, y, 2, -2, y, 2});
        stack.indices.insert(stack.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    }
    s.meshes.push_back(stack);
    s.instances = {{0, glm::mat4(1.0f)}, {1, glm::mat4(1.0f)}};
    s.environment.skyRadiance = glm::vec3(1.0f);
    s.camera = {glm::vec3(0, 3.5f, 2.5f), glm::vec3(0), glm::vec3(0, 1, 0), 45.0f};
    s.computeBounds();
    return s;
}

void raysAtAlphaBoundCounted(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    render::RasterOptions o;
    o.width = o.height = 32;
    o.lightSamples = 1;
    o.gi = true;
    auto counted = [&](uint32_t cards) {
        std::string error;
        auto r = render::RasterRenderer::create(*td.device, floorUnderCards(cards), o, &error);
        INFO(error);
        REQUIRE(r);
        frames(td, *r, 2);
        return r->giContext()->raysAtAlphaBound();
    };
    const uint64_t few = counted(3), many = counted(12);
    INFO("rays at the bound under 3 cards: " << few << ", under 12: " << many);
    CHECK(many > 100);
    CHECK(many > 2 * few);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("foliage: GI rays that reach the bound on cards passed are counted", "[gi]", raysAtAlphaBoundCounted)
BACKEND_TEST("foliage: the path tracer and the G-buffer see the same grass and leaves", "[render][quick]", foliageRenders)
BACKEND_TEST("foliage: the first frame's alpha pass fills the cells of the bricks that frame built", "[gi]", alphaCellsOfNewBricks)
BACKEND_TEST("foliage: bad generated textures are refused naming the mesh", "[render]", badGeneratedTextures)
BACKEND_TEST("foliage: the SDF GI's alpha-aware cards against built-opaque and left-out ones, and the path tracer", "[gi]",
             giFoliageVariants)

TEST_CASE("foliage: the scene holds alpha-tested grass and leaf cards with generated textures", "[metrics]") {
    std::string error;
    const scenes::SceneGeometry s = scenes::loadScene("foliage", &error);
    INFO(error);
    REQUIRE(!s.meshes.empty());
    CHECK(std::string(scenes::builtinSceneNames()).find("foliage") != std::string::npos);
    CHECK(s.name == "foliage");
    for (const char* name : {"grass", "leaves"}) {
        INFO(name);
        const scenes::TriangleMesh* m = meshNamed(s, name);
        REQUIRE(m);
        CHECK(m->alphaCutoff == 0.5f);
        REQUIRE(m->generatedTexture);
        const scenes::GeneratedTexture& t = *m->generatedTexture;
        CHECK(t.rgba.size() == size_t(t.width) * t.height * 4);
        CHECK(m->uvs.size() / 2 == m->positions.size() / 3);
        const double c = coverage(t);
        INFO("coverage " << c);
        CHECK(c > 0.25);
        CHECK(c < 0.6);
    }
    for (const char* name : {"ground", "wall", "trunk"}) {
        INFO(name);
        const scenes::TriangleMesh* m = meshNamed(s, name);
        REQUIRE(m);
        CHECK(!m->alphaTested());
    }
    CHECK(meshNamed(s, "grass")->triangleCount() > 5000);
    CHECK(s.triangleCount() <= 40000);
    CHECK(glm::length(s.environment.sunIrradiance) > 0.0f);
    CHECK(glm::length(s.environment.skyRadiance) > 0.0f);
    // The same scene every time (a fixed seed).
    const scenes::SceneGeometry again = scenes::foliage();
    CHECK(again.meshes[3].positions == s.meshes[3].positions);
    CHECK(again.meshes[3].generatedTexture->rgba == s.meshes[3].generatedTexture->rgba);
}
