// Alpha-tested materials in the voxelization (BL_VOXEL_COVERAGE, bricklight/voxelize.glsl) on both backends: a
// card whose coverage hook gives stripes of a known share makes voxels whose opacity and light average that
// share of a solid card's (fine stripes, coarse ones, stripes in phase with a fixed 4 × 4 sample grid, a tilted
// card reading the stripes from its user vector); the words are the same at every re-voxelization and after
// the clip-map scrolls; NaN and values outside [0, 1] are handled as documented, a coverage of 1 writes the
// opaque material's words; the compute voxelizer of registered meshes writes the draws' words.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "backend_test.h"
#include "bricklight/vct_scene.h"
#include "test_device.h"
#include "voxelize_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

const glm::vec3 kAnchor(16.5f, 16.5f, 16.5f);  // level 0 at world [0, 32)³
const glm::vec3 kRadiance(1.0f, 0.5f, 0.25f);
// The tolerance on a card's mean coverage: the jittered 4 × 4 points per pixel leave each voxel's estimate
// noisy (16 samples), and the card's border columns hold parts of a stripe; over ~400 voxels the mean is
// within 0.03 of the share in every case measured (the figures are printed).
constexpr float kMeanTolerance = 0.04f;

vct::ClipmapDesc coverageDesc() {
    vct::ClipmapDesc d;
    d.levels = 2;
    d.resolution = 32;
    d.finestVoxelSize = 1.0f;
    d.emittance = vct::EmittanceMode::Anisotropic;
    d.persistent = false;  // every update rewrites everything: each draw starts from empty volumes
    return d;
}

vct::VoxelMaterial thinMaterial() {
    vct::VoxelMaterial m;
    m.thickness = 0.0f;  // one voxel per column of a flat card
    return m;
}

// The hook's constants (tests/vct/shaders/coverage_hook.glsl).
struct Stripes {
    glm::vec4 shape{0.3f, 0.5f, 0.0f, 0.0f};  // period, covered share, axis (0 x, 1 y), 1: read user0
    glm::vec4 mode{0.0f};                     // 0 stripes, 1 NaN, 2 the constant mode.y
};
Stripes stripes(float period, float share, int axis = 0, bool fromUser = false) {
    Stripes s;
    s.shape = glm::vec4(period, share, float(axis), fromUser ? 1.0f : 0.0f);
    return s;
}
Stripes constantCoverage(float value) {
    Stripes s;
    s.mode = glm::vec4(2.0f, value, 0.0f, 0.0f);
    return s;
}

// A square card over x, y in [lo, hi], tilted about the x axis by `tilt` radians around y = 16 (the projection
// stays along z), front towards +z.
std::vector<Triangle> card(float lo, float hi, float z, float tilt = 0.0f) {
    auto at = [&](float x, float y) { return glm::vec3(x, y, z + (y - 16.0f) * std::tan(tilt)); };
    const glm::vec3 n = glm::normalize(glm::vec3(0.0f, -std::tan(tilt), 1.0f));
    const glm::vec3 a = at(lo, lo), b = at(hi, lo), c = at(hi, hi), d = at(lo, hi);
    return {{{a, b, c}, n}, {{a, c, d}, n}};
}

struct Words {
    std::vector<uint32_t> opacity;
    std::vector<float> emittance;
};

float zOpacity(uint32_t word) { return float((word >> 16) & 255u) / 255.0f; }

// The card's level-0 voxels (those the solid card makes opaque along z): how much of the solid card's opacity
// along z and light towards +z the covered one has, and the spread of its voxels' opacity.
struct CardShare {
    float opacity = 0.0f, light = 0.0f, spread = 0.0f;
    uint32_t voxels = 0;
};
CardShare shareOf(VoxelizeHarness& h, const Words& solid, const Words& covered) {
    double solidOpacity = 0.0, coveredOpacity = 0.0, solidLight = 0.0, coveredLight = 0.0;
    std::vector<float> ratios;
    for (int z = 0; z < 32; ++z)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                const size_t texel = h.texelIndex(0, {x, y, z});
                const float s = zOpacity(solid.opacity[texel]);
                for (uint32_t c = 0; c < 3; ++c) {
                    solidLight += solid.emittance[h.wordIndex(0, {x, y, z}, 2 * 3 + c)];  // +Z
                    coveredLight += covered.emittance[h.wordIndex(0, {x, y, z}, 2 * 3 + c)];
                }
                if (s == 0.0f) {
                    CHECK(covered.opacity[texel] == 0u);  // nothing where the solid card is not
                    continue;
                }
                solidOpacity += s;
                coveredOpacity += zOpacity(covered.opacity[texel]);
                ratios.push_back(zOpacity(covered.opacity[texel]) / s);
            }
    CardShare share;
    share.voxels = uint32_t(ratios.size());
    share.opacity = float(coveredOpacity / std::max(solidOpacity, 1e-9));
    share.light = float(coveredLight / std::max(solidLight, 1e-9));
    double variance = 0.0;
    for (float r : ratios) variance += (r - share.opacity) * (r - share.opacity);
    share.spread = float(std::sqrt(variance / std::max<size_t>(ratios.size(), 1)));
    return share;
}

class CoverageRig {
public:
    explicit CoverageRig(TestDevice& td) : td_(td), harness_(td, coverageDesc()) {
        rhi::ShaderDesc sd;
        sd.blob = rhi::findShader("vct_tests/voxelize_coverage.frag");
        REQUIRE(sd.blob);
        coverage_ = td.device->createShader(sd);
        REQUIRE(coverage_);
    }
    ~CoverageRig() { td_.device->destroy(coverage_); }
    VoxelizeHarness& harness() { return harness_; }
    rhi::ShaderHandle coverageShader() const { return coverage_; }

    // One frame: the clip-map rewritten whole around `anchor`, the triangles drawn with the coverage hook (or,
    // `hook` null, with the emissive test shader and no hook: the opaque material).
    Words voxelize(const std::vector<Triangle>& triangles, const Stripes* hook, const glm::vec3& anchor = kAnchor) {
        Error error;
        REQUIRE(harness_.clipmap().update(anchor, &error));
        vct::VoxelMaterial m = thinMaterial();
        const glm::vec4 emission(kRadiance, 0.0f);
        if (hook) {
            m.fragmentShader = coverage_;
            harness_.draw(triangles, m, &kRadiance, {rhi::constants(0, emission), rhi::constants(1, *hook)});
        } else {
            harness_.draw(triangles, m, &kRadiance);
        }
        harness_.clipmap().finishVoxelization();
        return {harness_.opacity(), harness_.emittance()};
    }

private:
    TestDevice& td_;
    VoxelizeHarness harness_;
    rhi::ShaderHandle coverage_;
};

void coverageWeightsOpacityAndLight(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    CoverageRig rig(td);
    struct Case {
        const char* name;
        std::vector<Triangle> triangles;
        Stripes hook;
    };
    const std::vector<Triangle> flat = card(6.5f, 25.5f, 10.5f), tilted = card(6.5f, 25.5f, 12.5f, 0.4f);
    const Case cases[] = {
        {"fine stripes (0.3 voxel), 25 %", flat, stripes(0.3f, 0.25f)},
        {"fine stripes (0.3 voxel), 50 %", flat, stripes(0.3f, 0.5f)},
        {"coarse stripes (4 voxels), 50 %", flat, stripes(4.0f, 0.5f)},
        // In phase with a fixed 4 × 4 grid (points at 1/8 + k/4: all in the uncovered half); the jitter finds
        // the share anyway.
        {"stripes in phase with a 4 x 4 grid (0.25 voxel), 50 %", flat, stripes(0.25f, 0.5f)},
        {"tilted card, stripes along y from user0 (0.3 voxel), 40 %", tilted, stripes(0.3f, 0.4f, 1, true)},
    };
    for (const Case& c : cases) {
        INFO(backend << ": " << c.name);
        const Words solid = rig.voxelize(c.triangles, nullptr);
        const Words covered = rig.voxelize(c.triangles, &c.hook);
        const CardShare share = shareOf(rig.harness(), solid, covered);
        std::printf("vct coverage [%s] %s: %u voxels, opacity %.3f of the solid card's (per-voxel spread %.3f), light %.3f; share %.2f\n",
                    backend.c_str(), c.name, share.voxels, share.opacity, share.spread, share.light, c.hook.shape.y);
        CHECK(share.voxels >= 300);
        CHECK(share.opacity == Approx(c.hook.shape.y).margin(kMeanTolerance));
        CHECK(share.light == Approx(c.hook.shape.y).margin(kMeanTolerance));
    }
    REQUIRE_NO_MESSAGES(td);
}

size_t differingWords(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
    REQUIRE(a.size() == b.size());
    size_t n = 0;
    for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
    return n;
}

// Light channels (six directions) that differ (kLightDifferenceBound: none).
size_t differingLight(const std::vector<float>& a, const std::vector<float>& b) {
    return radianceDifferences(a, b, a.size() / 18, kLightDifferenceBound);
}

void coverageIsStable(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    CoverageRig rig(td);
    VoxelizeHarness& h = rig.harness();
    const std::vector<Triangle> flat = card(6.5f, 25.5f, 10.5f);
    const Stripes hook = stripes(0.3f, 0.4f);
    const Words solid = rig.voxelize(flat, nullptr);
    const Words first = rig.voxelize(flat, &hook);
    const CardShare share = shareOf(h, solid, first);
    CHECK(share.opacity == Approx(0.4f).margin(kMeanTolerance));  // partly covered, not solid
    // Frame after frame: the same words, opacity and light.
    for (int frame = 0; frame < 3; ++frame) {
        const Words again = rig.voxelize(flat, &hook);
        CHECK(differingWords(again.opacity, first.opacity) == 0);
        CHECK(differingLight(again.emittance, first.emittance) == 0);
    }
    // The clip-map scrolled: the card's voxels keep their words (the points hash world coordinates).
    const Words scrolled = rig.voxelize(flat, &hook, kAnchor + glm::vec3(2.0f, 4.0f, 0.0f));
    REQUIRE(h.clipmap().placement().origin(0) == glm::ivec3(2, 4, 0));
    size_t compared = 0, differing = 0;
    for (int y = 6; y <= 26; ++y)
        for (int x = 6; x <= 26; ++x) {
            // texelIndex is toroidal: the same world voxel's texel in both placements.
            const size_t texel = h.texelIndex(0, {x, y, 10});
            if (first.opacity[texel] == 0u) continue;
            ++compared;
            differing += scrolled.opacity[texel] != first.opacity[texel];
        }
    CHECK(compared >= 300);
    CHECK(differing == 0);
    // The hook reading the stripes from user0 (the position, interpolated by the rasterizer and carried to the
    // points by its derivatives) writes what it writes from the position, but for points within rounding of a
    // stripe's edge.
    const Stripes fromUser = stripes(0.3f, 0.4f, 0, true);
    const Words user = rig.voxelize(flat, &fromUser);
    const size_t userDiffers = differingWords(user.opacity, first.opacity);
    std::printf("vct coverage [%s] stable over 3 frames and a scroll (%zu voxels); user0 vs position: %zu of %zu voxels differ\n",
                backend.c_str(), compared, userDiffers, size_t(share.voxels));
    CHECK(userDiffers <= share.voxels / 20);
    REQUIRE_NO_MESSAGES(td);
}

void coverageHandlesBadValuesAndOpaque(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    CoverageRig rig(td);
    const std::vector<Triangle> flat = card(6.5f, 25.5f, 10.5f), tilted = card(6.5f, 25.5f, 12.5f, 0.4f);
    for (const std::vector<Triangle>* triangles : {&flat, &tilted}) {
        const Words solid = rig.voxelize(*triangles, nullptr);
        REQUIRE(std::count_if(solid.opacity.begin(), solid.opacity.end(), [](uint32_t w) { return w != 0; }) >= 300);
        // Covered everywhere: the opaque material's opacity words, bit for bit, and its light.
        const Stripes full = stripes(0.3f, 1.0f), nan = [] { Stripes s; s.mode.x = 1.0f; return s; }();
        for (const Stripes& hook : {full, nan, constantCoverage(7.0f), constantCoverage(1.0f)}) {
            INFO(backend << ": mode " << hook.mode.x << ", value " << hook.mode.y);
            const Words w = rig.voxelize(*triangles, &hook);
            CHECK(differingWords(w.opacity, solid.opacity) == 0);
            CHECK(differingLight(w.emittance, solid.emittance) == 0);
        }
        // Negative (clamped to 0) and 0: nothing at all.
        for (float value : {-7.0f, 0.0f}) {
            const Stripes hook = constantCoverage(value);
            const Words w = rig.voxelize(*triangles, &hook);
            CHECK(std::count_if(w.opacity.begin(), w.opacity.end(), [](uint32_t x) { return x != 0; }) == 0);
            CHECK(std::count_if(w.emittance.begin(), w.emittance.end(), [](float x) { return x != 0.0f; }) == 0);
        }
    }
    REQUIRE_NO_MESSAGES(td);
}

// Registered meshes: the coverage hook in the material's computeShader gives the draws' words. (Their user
// vectors are the instance's, so a registered mesh's coverage can depend on the position, not on texture
// coordinates.)
void computeVoxelizerWritesTheDrawsCoverage(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("vct_tests/voxelize_coverage.comp");
    REQUIRE(sd.blob);
    const rhi::ShaderHandle coverageCompute = td.device->createShader(sd);
    REQUIRE(coverageCompute);
    const glm::vec4 emission(kRadiance, 0.0f);
    const Stripes hook = stripes(0.3f, 0.4f);
    rhi::Bindings extra;
    extra.constants.push(rhi::constants(0, emission));
    extra.constants.push(rhi::constants(1, hook));
    std::vector<float> positions, normals;
    std::vector<uint32_t> indices;
    for (const std::vector<Triangle>& c : {card(6.5f, 25.5f, 10.5f), card(6.5f, 25.5f, 14.5f, 0.4f), card(3.25f, 5.75f, 20.5f)})
        for (const Triangle& t : c)
            for (const glm::vec3& p : t.p) {
                positions.insert(positions.end(), {p.x, p.y, p.z});
                normals.insert(normals.end(), {t.normal.x, t.normal.y, t.normal.z});
                indices.push_back(uint32_t(indices.size()));
            }
    Words words[2];
    Error error;
    for (int compute = 0; compute < 2; ++compute) {
        INFO(backend << (compute ? ": compute" : ": draws"));
        CoverageRig rig(td);
        auto scene = vct::VoxelScene::create(*td.device, &error);
        REQUIRE(scene);
        if (compute) scene->setVoxelizer(vct::Voxelizer::Compute, vct::ComputeVoxelizer{1.0e6f});  // none drawn
        vct::VoxelMeshArrays arrays;
        arrays.positions = positions.data();
        arrays.normals = normals.data();
        arrays.vertexCount = uint32_t(positions.size() / 3);
        arrays.indices = indices.data();
        arrays.indexCount = uint32_t(indices.size());
        arrays.name = "cards";
        vct::VoxelInstanceDesc id;
        id.mesh = scene->createMesh(arrays, &error);
        REQUIRE(id.mesh);
        id.material = thinMaterial();
        id.material.fragmentShader = rig.coverageShader();
        id.material.computeShader = coverageCompute;
        REQUIRE(scene->addInstance(id, &error));
        REQUIRE(rig.harness().clipmap().update(kAnchor, &error, scene->takeDirtyRegions()));
        REQUIRE(scene->voxelize(rig.harness().clipmap(), extra, &error));
        CHECK(scene->lastComputeCount() == uint32_t(compute));
        rig.harness().clipmap().finishVoxelization();
        words[compute] = {rig.harness().opacity(), rig.harness().emittance()};
        if (!compute) {
            const Words solid = rig.voxelize(card(6.5f, 25.5f, 10.5f), nullptr);
            const Words flatOnly = rig.voxelize(card(6.5f, 25.5f, 10.5f), &hook);
            CHECK(shareOf(rig.harness(), solid, flatOnly).opacity == Approx(0.4f).margin(kMeanTolerance));
        }
    }
    CHECK(std::count_if(words[0].opacity.begin(), words[0].opacity.end(), [](uint32_t w) { return w != 0; }) >= 500);
    const size_t opacityDiffers = differingWords(words[1].opacity, words[0].opacity);
    const size_t lightDiffers = differingLight(words[1].emittance, words[0].emittance);
    std::printf("vct coverage [%s] compute vs draws: %zu opacity words and %zu light channels differ\n", backend.c_str(),
                opacityDiffers, lightDiffers);
    CHECK(opacityDiffers == 0);
    CHECK(lightDiffers == 0);
    td.device->destroy(coverageCompute);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("voxel coverage: a card's opacity and light average its coverage", "[vct]", coverageWeightsOpacityAndLight)
BACKEND_TEST("voxel coverage: the words are stable over frames and scrolling", "[vct]", coverageIsStable)
BACKEND_TEST("voxel coverage: NaN and out-of-range values, and full coverage as opaque", "[vct]", coverageHandlesBadValuesAndOpaque)
BACKEND_TEST("voxel coverage: the compute voxelizer writes the draws' words", "[vct]", computeVoxelizerWritesTheDrawsCoverage)
