// Hybrid shadows through foliage (issue 22; ShadowClassifyDesc::alphaCache): a floor under an upright alpha-tested
// card whose alpha test keeps stripes over a known share of it, the sun 45° up behind the card, the GI's alpha cache
// filled by one alpha pass (tests/sdf/shaders/alpha_pass_card.vert + alpha_pass_stripes.frag). The floor pixels in
// the card's shadow, averaged over frames (frameIndex varying), are lit by about 1 − the share with every kind of
// ray (hard, sure, soft through the shadow denoiser); without the alpha cache, with a GI context that keeps none and
// with a fully covered card they are fully shadowed; the open floor stays lit; a bad alpha cache is refused. Both
// backends, the validation layer and our wrapper on.
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "backend_test.h"
#include "bricklight/shadows/classifier.h"
#include "bricklight/gi.h"
#include "bricklight/shadows/denoiser.h"
#include "test_device.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

constexpr uint32_t kWidth = 64, kHeight = 32;  // the floor over x −2..2, z −2..0: 1/16 unit a pixel
constexpr uint32_t kFrames = 32;
// The card: x −1..1, y 0.35..1.45 at z = 0.013 (off the voxel boundaries), u across x. The sun's rays from the floor
// cross it at 45°: its shadow covers x −1..1, z −1.437..−0.337.
constexpr float kCardZ = 0.013f, kCardBottom = 0.35f, kCardTop = 1.45f;
constexpr float kStripePeriods = 61.7f;  // a period of 3.2 cm (1.3 of the finest cascade's 2.5 cm cells): coverage in
                                         // every cell is partial, so the rays' draws decide, not the cells' layout
constexpr float kShare = 0.4f;           // of each period the alpha test keeps
const glm::vec3 kSun = glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f));

enum class Region { Shadow, Open, Edge };

struct Floor {
    glm::mat4 view{1.0f}, projection{1.0f};
    std::vector<float> depth;
    std::vector<glm::vec4> normals;
    std::vector<Region> region;
    rhi::TextureHandle depthTexture, normalTexture;
};

// Looking straight down at the floor (y = 0) with an orthographic camera. The shadow region keeps 0.15 units off the
// shadow's outline (where the card's edges and the field's rounding decide); the open floor 0.2 units.
Floor makeFloor(rhi::IDevice& dev) {
    Floor f;
    f.view = glm::lookAtRH(glm::vec3(0.0f, 10.0f, -1.0f), glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    f.projection = glm::orthoRH_ZO(-2.0f, 2.0f, -1.0f, 1.0f, 0.1f, 20.0f);
    f.projection[1][1] = -f.projection[1][1];  // NDC y −1 at the top row (the library's convention)
    const glm::mat4 viewProjection = f.projection * f.view, inverse = glm::inverse(viewProjection);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const glm::vec2 ndc((float(x) + 0.5f) / kWidth * 2.0f - 1.0f, (float(y) + 0.5f) / kHeight * 2.0f - 1.0f);
            const glm::vec4 w = inverse * glm::vec4(ndc, 0.5f, 1.0f);
            const glm::vec2 g(w.x / w.w, w.z / w.w);
            const glm::vec4 clip = viewProjection * glm::vec4(g.x, 0.0f, g.y, 1.0f);
            f.depth.push_back(clip.z / clip.w);
            f.normals.push_back(glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
            // The sun's ray from (x, 0, z) meets the card's plane at height kCardZ − z.
            const float height = kCardZ - g.y, margin = std::abs(g.x) - 1.0f;
            const float inside = std::max(margin, std::max(kCardBottom - height, height - kCardTop));  // < 0: behind the card
            f.region.push_back(inside < -0.15f ? Region::Shadow : inside > 0.2f ? Region::Open : Region::Edge);
        }
    rhi::TextureDesc d;
    d.width = kWidth;
    d.height = kHeight;
    d.format = rhi::Format::R32_FLOAT;
    d.usage = rhi::TextureUsage::Sampled;
    d.debugName = "foliage test depth";
    f.depthTexture = dev.createTexture(d, f.depth.data());
    d.format = rhi::Format::RGBA32_FLOAT;
    d.debugName = "foliage test normals";
    f.normalTexture = dev.createTexture(d, f.normals.data());
    REQUIRE(f.depthTexture);
    REQUIRE(f.normalTexture);
    return f;
}

// The distance field: an opaque floor slab and the alpha-tested card, cascade 0 (0.1-unit voxels) over all of it.
std::unique_ptr<sdf::SdfScene> makeField(TestDevice& td) {
    sdf::SceneDesc sd;
    sd.cascadeCount = 3;
    sd.finestVoxelSize = 0.1f;
    sd.atlasBricksPerAxis = 32;
    sd.errorCallback = [&td](rhi::Severity, const std::string& m) { td.messages->push_back(m); };
    Error error;
    auto field = sdf::SdfScene::create(*td.device, sd, &error);
    INFO(error.message);
    REQUIRE(field);
    const float floorPositions[] = {-3, -0.3f, -3, 3, -0.3f, -3, -3, 0, -3, 3, 0, -3, -3, -0.3f, 3, 3, -0.3f, 3, -3, 0, 3, 3, 0, 3};
    const uint32_t floorIndices[] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    const float cardPositions[] = {-1, kCardBottom, kCardZ, 1, kCardBottom, kCardZ, 1, kCardTop, kCardZ, -1, kCardTop, kCardZ};
    const uint32_t cardIndices[] = {0, 1, 2, 0, 2, 3};
    const sdf::MeshHandle floorMesh = field->createMesh({floorPositions, 8, floorIndices, 36, "floor"});
    const sdf::MeshHandle cardMesh = field->createMesh({cardPositions, 4, cardIndices, 6, "card"});
    REQUIRE(floorMesh);
    REQUIRE(cardMesh);
    REQUIRE(field->addInstance({floorMesh, glm::mat4(1.0f)}));
    sdf::InstanceDesc card;
    card.mesh = cardMesh;
    card.alphaTested = true;
    REQUIRE(field->addInstance(card));
    for (int i = 0; i < 8 && field->update(glm::vec3(0.0f, 0.5f, -0.5f)).jobsDeferred != 0; ++i) {
    }
    return field;
}

// A GI context over the field (with or without the alpha cache); with it, one alpha pass over the card whose
// stripes keep `share` of each period.
std::unique_ptr<gi::GiContext> makeGi(TestDevice& td, sdf::SdfScene& field, bool alphaCache, float share) {
    rhi::IDevice& dev = *td.device;
    gi::ContextDesc cd;
    cd.displayWidth = kWidth;
    cd.displayHeight = kHeight;
    cd.flags = alphaCache ? gi::ContextFlags::AlphaCache : 0u;
    cd.errorCallback = [&td](rhi::Severity, const std::string& m) { td.messages->push_back(m); };
    Error error;
    std::unique_ptr<gi::GiContext> context = gi::GiContext::create(dev, field, cd, &error);
    INFO(error.message);
    REQUIRE(context);
    if (!alphaCache) return context;
    rhi::ShaderDesc vd, fd;
    vd.blob = rhi::findShader("sdf_tests/alpha_pass_card.vert");
    fd.blob = rhi::findShader("sdf_tests/alpha_pass_stripes.frag");
    REQUIRE(vd.blob);
    REQUIRE(fd.blob);
    const rhi::ShaderHandle vertex = dev.createShader(vd), fragment = dev.createShader(fd);
    const float vertices[] = {-1, kCardBottom, kCardZ, 0, 0, 1, kCardBottom, kCardZ, 1, 0, 1, kCardTop, kCardZ, 1, 1,
                              -1, kCardBottom, kCardZ, 0, 0, 1, kCardTop,    kCardZ, 1, 1, -1, kCardTop, kCardZ, 0, 1};
    rhi::BufferDesc bd;
    bd.size = sizeof(vertices);
    bd.usage = rhi::BufferUsage::Vertex;
    bd.debugName = "card vertices";
    const rhi::BufferHandle vertexBuffer = dev.createBuffer(bd, vertices);
    std::optional<rhi::DrawCallState> s = context->alphaPassState(fragment, &error);
    INFO(error.message);
    REQUIRE(s);
    s->vertexShader = vertex;
    s->vertexInputs.push({0, rhi::VertexFormat::Float3, 0, 0});
    s->vertexInputs.push({1, rhi::VertexFormat::Float2, 0, 12});
    s->vertexBuffers.push({vertexBuffer, 0, 20, false});
    const glm::vec4 stripes(share, kStripePeriods, 0.0f, 0.0f);
    s->bindings.constants.push(rhi::constants(0, stripes));
    rhi::DrawArgs args;
    args.vertexCount = 6;
    REQUIRE(dev.draw(*s, args));
    dev.destroy(vertexBuffer);
    dev.destroy(vertex);
    dev.destroy(fragment);
    return context;
}

float halfToFloat(uint16_t h) {
    switch (h) {
    case 0x3C00: return 1.0f;
    case 0x0000: return 0.0f;
    case 0xBC00: return -1.0f;  // unsure (markUnsurePixels)
    default: {                  // the denoiser's values in between
        const uint32_t sign = (h >> 15) & 1u, exponent = (h >> 10) & 31u, mantissa = h & 1023u;
        const float m = exponent == 0 ? float(mantissa) / 1024.0f * std::ldexp(1.0f, -14)
                                      : (1.0f + float(mantissa) / 1024.0f) * std::ldexp(1.0f, int(exponent) - 15);
        return sign ? -m : m;
    }
    }
}

enum class Rays { Hard, Sure, SoftDenoised };

struct Visibility {
    double shadowLit = 0.0;       // the shadow region's mean lit fraction over the frames (sure answers only)
    double openLit = 0.0;         // the open floor's
    double partialPixels = 0.0;   // the share of the shadow region's pixels lit in some frames and not in others
    double unsure = 0.0;          // the share of the shadow region's answers left to the maps (sure rays)
    size_t shadowPixels = 0, openPixels = 0;
};

// kFrames frames of classify (normals mode: every floor pixel a ray) + trace + resolve (or the denoiser), frameIndex
// 0, 1, ...; hard and sure rays average the resolved masks, soft ones take the denoiser's last output.
Visibility traceFrames(TestDevice& td, const Floor& f, sdf::SdfScene& field, rhi::BufferHandle alphaCache, Rays rays) {
    rhi::IDevice& dev = *td.device;
    Error error;
    auto classifier = shadows::ShadowClassifier::create(dev, {kWidth, kHeight}, &error);
    INFO(error.message);
    REQUIRE(classifier);
    std::unique_ptr<shadows::ShadowDenoiser> denoiser;
    if (rays == Rays::SoftDenoised) REQUIRE((denoiser = shadows::ShadowDenoiser::create(dev, {kWidth, kHeight}, &error)));
    rhi::TextureDesc md;
    md.width = kWidth;
    md.height = kHeight;
    md.format = rhi::Format::R16_FLOAT;
    md.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    md.debugName = "foliage test shadow mask";
    const rhi::TextureHandle mask = dev.createTexture(md);
    REQUIRE(mask);
    shadows::ShadowClassifyDesc d;
    d.mode = shadows::ShadowClassifyMode::Normals;
    d.camera.view = f.view;
    d.camera.projection = f.projection;
    d.gbuffer.depth = f.depthTexture;
    d.gbuffer.normals = f.normalTexture;
    d.gbuffer.normalsUnpackScale = glm::vec3(1.0f);
    d.gbuffer.normalsUnpackOffset = glm::vec3(0.0f);
    d.sunDirection = kSun;
    d.alphaCache = alphaCache;
    d.sureRaysOnly = d.markUnsurePixels = rays == Rays::Sure;
    if (rays == Rays::SoftDenoised) {
        d.softShadows = true;
        d.sunAngle = 0.02f;  // a penumbra of about 3 cm at the card's top: within the region's margin
    }
    std::vector<double> litSum(f.depth.size(), 0.0);
    std::vector<uint32_t> sureCount(f.depth.size(), 0), litCount(f.depth.size(), 0);
    std::vector<uint16_t> halves(f.depth.size());
    for (uint32_t frame = 0; frame < kFrames; ++frame) {
        d.frameIndex = frame;
        REQUIRE(classifier->classify(d, &error));
        REQUIRE(classifier->trace(field, &error));
        if (denoiser) {
            shadows::ShadowDenoiseDesc n;
            n.camera.view = n.camera.previousView = f.view;
            n.camera.projection = n.camera.previousProjection = f.projection;
            n.gbuffer.depth = f.depthTexture;
            n.gbuffer.normals = f.normalTexture;
            n.gbuffer.normalsUnpackScale = glm::vec3(1.0f);
            n.gbuffer.normalsUnpackOffset = glm::vec3(0.0f);
            n.output = mask;
            n.resetHistory = frame == 0;
            REQUIRE(denoiser->denoise(*classifier, n, &error));
        } else {
            REQUIRE(classifier->resolve(mask, &error));
        }
        if (denoiser && frame + 1 < kFrames) continue;
        REQUIRE(dev.readTexture(mask, {}, halves.data()));
        for (size_t i = 0; i < halves.size(); ++i) {
            const float v = halfToFloat(halves[i]);
            if (v < 0.0f) continue;
            litSum[i] += v;
            ++sureCount[i];
            litCount[i] += v > 0.5f;
        }
    }
    Visibility r;
    double shadowSure = 0.0, openSure = 0.0, answers = 0.0;
    for (size_t i = 0; i < f.depth.size(); ++i) {
        if (f.region[i] == Region::Shadow) {
            ++r.shadowPixels;
            r.shadowLit += litSum[i];
            shadowSure += sureCount[i];
            answers += denoiser ? 1.0 : kFrames;
            r.partialPixels += litCount[i] > 0 && litCount[i] < sureCount[i];
        } else if (f.region[i] == Region::Open) {
            ++r.openPixels;
            r.openLit += litSum[i];
            openSure += sureCount[i];
        }
    }
    r.shadowLit /= std::max(1.0, shadowSure);
    r.openLit /= std::max(1.0, openSure);
    r.unsure = 1.0 - shadowSure / std::max(1.0, answers);
    r.partialPixels /= std::max<size_t>(1, r.shadowPixels);
    dev.destroy(mask);
    return r;
}

void litThroughTheCutOutShare(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    REQUIRE(td.device->capabilities().geometryShader);  // the alpha pass: both reference drivers offer them
    Floor f = makeFloor(*td.device);
    auto field = makeField(td);
    auto gi = makeGi(td, *field, true, kShare);
    // The coverage the pass left in the cache, over the cells it reached (the share as its fragments sampled it).
    std::vector<uint32_t> fragments;
    const std::vector<float> coverage = gi->readAlphaCoverage(&fragments);
    double covered = 0.0, counted = 0.0;
    for (size_t i = 0; i < coverage.size(); ++i)
        if (coverage[i] >= 0.0f) {
            covered += double(coverage[i]) * fragments[i];
            counted += fragments[i];
        }
    const double cachedShare = covered / std::max(1.0, counted);
    for (Rays rays : {Rays::Hard, Rays::Sure, Rays::SoftDenoised}) {
        const char* name = rays == Rays::Hard ? "hard rays" : rays == Rays::Sure ? "sure rays" : "soft rays, denoised";
        const Visibility v = traceFrames(td, f, *field, gi->alphaCacheBuffer(), rays);
        WARN(backend << ", " << name << ": the shadow's " << v.shadowPixels << " pixels lit " << v.shadowLit << " over " << kFrames << " frames (1 - share "
                           << 1.0 - kShare << ", 1 - the cache's coverage " << 1.0 - cachedShare << "); partial pixels " << v.partialPixels
                           << ", unsure answers " << v.unsure << "; open floor (" << v.openPixels << " pixels) lit " << v.openLit);
        CHECK(v.shadowPixels > 250);
        CHECK(v.openPixels > 400);
        CHECK(std::abs(v.shadowLit - (1.0 - kShare)) < 0.05);
        CHECK(v.openLit == 1.0);
        if (rays != Rays::SoftDenoised) CHECK(v.partialPixels > 0.5);  // the draws vary over frames
        if (rays == Rays::Sure) CHECK(v.unsure < 0.01);  // measured 0 (9 % before the fat ray followed the thin one's cards)
    }
    REQUIRE_NO_MESSAGES(td);
    gi.reset();
    field.reset();
    for (rhi::TextureHandle t : {f.depthTexture, f.normalTexture}) td.device->destroy(t);
}

// The card solid to the rays: without an alpha cache (the classifier's stand-in), with a GI context that keeps none
// (its stand-in buffer) and with the alpha test keeping all of the card.
void solidWithoutCoverage(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    REQUIRE(td.device->capabilities().geometryShader);
    Floor f = makeFloor(*td.device);
    auto field = makeField(td);
    auto covered = makeGi(td, *field, true, 1.0f);
    auto plain = makeGi(td, *field, false, 0.0f);
    const std::pair<const char*, rhi::BufferHandle> caches[] = {
        {"no alpha cache", rhi::BufferHandle{}}, {"a GI context without one", plain->alphaCacheBuffer()}, {"a fully covered card", covered->alphaCacheBuffer()}};
    for (const auto& [name, cache] : caches)
        for (Rays rays : {Rays::Hard, Rays::Sure}) {
            const Visibility v = traceFrames(td, f, *field, cache, rays);
            WARN(backend << ", " << name << (rays == Rays::Hard ? ", hard rays" : ", sure rays") << ": the shadow lit " << v.shadowLit << ", unsure " << v.unsure
                                << ", open floor lit " << v.openLit);
            CHECK(v.shadowLit == 0.0);
            CHECK(v.openLit == 1.0);
        }
    REQUIRE_NO_MESSAGES(td);
    covered.reset();
    plain.reset();
    field.reset();
    for (rhi::TextureHandle t : {f.depthTexture, f.normalTexture}) td.device->destroy(t);
}

void refusesBadAlphaCache(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    rhi::IDevice& dev = *td.device;
    Floor f = makeFloor(dev);
    auto field = makeField(td);
    Error error;
    auto c = shadows::ShadowClassifier::create(dev, {kWidth, kHeight}, &error);
    REQUIRE(c);
    shadows::ShadowClassifyDesc d;
    d.mode = shadows::ShadowClassifyMode::Normals;
    d.gbuffer.depth = f.depthTexture;
    d.gbuffer.normals = f.normalTexture;
    d.camera.view = f.view;
    d.camera.projection = f.projection;
    auto buffer = [&](uint64_t size, uint32_t usage) {
        rhi::BufferDesc bd;
        bd.size = size;
        bd.usage = usage;
        bd.debugName = "test alpha cache";
        const rhi::BufferHandle b = dev.createBuffer(bd);
        REQUIRE(b);
        return b;
    };
    auto refused = [&](rhi::BufferHandle cache, const char* expected) {
        d.alphaCache = cache;
        error = {};
        INFO("expected: " << expected << "; got: " << error.message);
        CHECK(!c->classify(d, &error));
        CHECK(error.message.find(expected) != std::string::npos);
    };
    const rhi::BufferHandle readOnly = buffer(64, rhi::BufferUsage::ShaderRead), small = buffer(8, rhi::BufferUsage::ShaderWrite);
    const rhi::BufferHandle gone = buffer(16, rhi::BufferUsage::ShaderWrite);
    dev.destroy(gone);
    refused(readOnly, "BufferUsage::ShaderWrite");
    refused(small, "16-byte header");
    refused(gone, "alphaCache is not a live buffer");
    // Destroyed between classify() and trace(): the trace is refused.
    const rhi::BufferHandle early = buffer(16, rhi::BufferUsage::ShaderWrite | rhi::BufferUsage::ShaderRead);
    d.alphaCache = early;
    REQUIRE(c->classify(d, &error));
    dev.destroy(early);
    error = {};
    CHECK(!c->trace(*field, &error));
    CHECK(error.message.find("alphaCache still live") != std::string::npos);
    dev.destroy(readOnly);
    dev.destroy(small);
    REQUIRE_NO_MESSAGES(td);
    c.reset();
    field.reset();
    for (rhi::TextureHandle t : {f.depthTexture, f.normalTexture}) dev.destroy(t);
}

}  // namespace

BACKEND_TEST("hybrid shadows through foliage: lit by the cut-out share, averaged over frames", "[classify][foliage]", litThroughTheCutOutShare)
BACKEND_TEST("hybrid shadows through foliage: solid without coverage", "[classify][foliage]", solidWithoutCoverage)
BACKEND_TEST("hybrid shadows through foliage: a bad alpha cache is refused", "[classify][foliage]", refusesBadAlphaCache)
