// Hybrid reflections in the renderer (ReflectionMode::Hybrid: the reflection classifier's screen-space and distance-
// field rays, denoised, over GI's specular) against the path tracer, on a mirror-like and a glossy metal floor, with
// GI's specular alone as the baseline they must beat; across backends; and the option's refusals. Bounds are stated
// where they are asserted; docs/reflections.md lists the figures.
#include <cmath>

#include "backend_test.h"
#include "bricklight/half.h"
#include "image_metrics.h"
#include "path_tracer.h"
#include "raster_renderer.h"
#include "shared_references.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

constexpr uint32_t kSize = 128;
constexpr uint32_t kFrames = 48;

// One bounce (feedback false): the lit image that GI and the reflections read holds direct light only, so that the
// comparison with the path tracer stopped after one bounce measures the reflections themselves, not GI's multi-bounce
// shortfall (the reflected surfaces' own indirect light, which both modes would inherit; docs/gi.md).
std::unique_ptr<render::RasterRenderer> reflectingRenderer(TestDevice& td, const scenes::SceneGeometry& scene, render::ReflectionMode mode,
                                                           bool feedback = false) {
    render::RasterOptions o;
    o.width = o.height = kSize;
    o.gi = true;
    o.giFeedback = feedback;
    o.reflections = mode;
    std::string error;
    auto r = render::RasterRenderer::create(*td.device, scene, o, &error);
    INFO(error);
    REQUIRE(r);
    return r;
}

// The metal floor's pixels: facing up and of the floor's albedo (0.9; the blocks' tops are 0.725).
std::vector<uint8_t> floorMask(render::RasterRenderer& r) {
    const render::Image normal = r.read(render::Aov::Normal), albedo = r.read(render::Aov::Albedo);
    std::vector<uint8_t> mask(size_t(normal.width) * normal.height, 0);
    for (size_t p = 0; p < mask.size(); ++p) mask[p] = normal.rgb[3 * p + 1] > 0.99f && albedo.rgb[3 * p] > 0.85f;
    return mask;
}

// An RGBA16_FLOAT texture's texels as floats (waits for the device).
std::vector<float> readRgba16f(TestDevice& td, rhi::TextureHandle t, uint32_t width, uint32_t height) {
    std::vector<uint16_t> h(size_t(width) * height * 4);
    REQUIRE(td.device->readTexture(t, {}, h.data()));
    std::vector<float> f(h.size());
    for (size_t i = 0; i < h.size(); ++i) f[i] = halfToFloat(h[i]);
    return f;
}

size_t count(const std::vector<uint8_t>& mask) {
    size_t n = 0;
    for (uint8_t m : mask) n += m;
    return n;
}

struct FloorResult {
    render::ImageMetrics gi, hybrid;
};

FloorResult floorAgainstReference(const std::string& backend, float roughness) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry scene = scenes::cornellMirror(roughness);
    auto gi = reflectingRenderer(td, scene, render::ReflectionMode::Gi);
    auto hybrid = reflectingRenderer(td, scene, render::ReflectionMode::Hybrid);
    frames(td, *gi, kFrames);
    frames(td, *hybrid, kFrames);
    REQUIRE(hybrid->reflectionClassifier());
    auto reference = mirrorFloorReference(td, roughness);  // kSize², 512 spp, one bounce
    const std::vector<uint8_t> mask = floorMask(*hybrid);
    REQUIRE(count(mask) > kSize * kSize / 16);  // about 9 % of the image
    const render::Image ref = reference.read(render::Aov::Combined);
    const render::Image a = gi->read(render::Aov::Combined), b = hybrid->read(render::Aov::Combined);
    REQUIRE(allFinite(b.rgb));
    FloorResult r{render::compareImages(a, ref, &mask), render::compareImages(b, ref, &mask)};
    const reflections::ReflectionClassifyCounts counts = hybrid->reflectionClassifier()->readCounts();
    WARN("floor pixels " << count(mask) << "; rays: screen " << counts.screenRays << " (hits " << counts.screenHits << ", misses "
                         << counts.screenMisses << "), SDF " << counts.sdfRays << ", glossy pixels " << counts.glossyPixels);
    WARN("GI's specular alone: relMSE " << r.gi.relMse << " SSIM " << r.gi.ssim << " mean " << r.gi.meanA << "; hybrid: relMSE "
                                        << r.hybrid.relMse << " SSIM " << r.hybrid.ssim << " mean " << r.hybrid.meanA << "; reference mean "
                                        << r.hybrid.meanB);
    // Every glossy floor pixel gets a ray (samplesPerQuad 4, roughness below the threshold 0.4).
    CHECK(counts.rayPixels >= count(mask));
    REQUIRE_NO_MESSAGES(td);
    return r;
}

void mirrorFloor(const std::string& backend) {
    // Roughness 0.05, one bounce, 48 frames, 128², against 512 spp. GI's specular reads the radiance cache (4³ texels
    // a brick, found through a pre-trace per 4×4 pixels), blurred and biased; the hybrid's screen-space rays read the
    // sharp lit image where the reflected surface is on screen (1497 of 1513 floor rays; 16 go on to the field).
    // Measured (lavapipe and llvmpipe alike): GI relMSE 0.0049, mean 0.00877 (116 % of the reference's 0.00756);
    // hybrid relMSE 0.00027, mean 0.00743 (98 %). Bounds: about twice the measured distance from perfect.
    const FloorResult r = floorAgainstReference(backend, 0.05f);
    CHECK(r.hybrid.relMse < 0.25 * r.gi.relMse);
    CHECK(r.hybrid.relMse < 0.0006);
    CHECK(std::abs(r.hybrid.meanA - r.hybrid.meanB) < 0.05 * r.hybrid.meanB);
    CHECK(std::abs(r.hybrid.meanA - r.hybrid.meanB) < std::abs(r.gi.meanA - r.gi.meanB));
    CHECK(r.hybrid.ssim > r.gi.ssim);
}

void glossyFloor(const std::string& backend) {
    // Roughness 0.3, otherwise as above: the lobe is wide, and 1324 of 1513 rays resolve on screen. Measured: GI relMSE
    // 0.0035, mean 0.01425 (98 % of 0.01455); hybrid relMSE 0.00083, mean 0.01300 (89 %). The hybrid is the closer
    // per pixel but the darker on average; its screen-space and SDF halves alone give 93 % and 92 %, so the shortfall
    // is common to both (not understood; docs/reflections.md "Limitations"). Bounds: relMSE about twice the measured;
    // the mean within 15 %.
    const FloorResult r = floorAgainstReference(backend, 0.3f);
    CHECK(r.hybrid.relMse < 0.5 * r.gi.relMse);
    CHECK(r.hybrid.relMse < 0.0015);
    CHECK(std::abs(r.hybrid.meanA - r.hybrid.meanB) < 0.15 * r.hybrid.meanB);
    CHECK(r.hybrid.ssim > r.gi.ssim);
}

void reflectionRaysRejectBadInput(const std::string& backend) {
    // GiContext::traceReflectionRays: each spoilt description fails with a message naming the resource and the
    // problem, and the output keeps what it held (nothing was recorded).
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    render::RasterOptions o;
    o.width = o.height = 32;
    o.gi = true;
    std::string error;
    auto r = render::RasterRenderer::create(*td.device, scenes::cornellMirror(0.05f), o, &error);
    INFO(error);
    REQUIRE(r);
    gi::GiContext* context = r->giContext();
    REQUIRE(context);
    rhi::BufferDesc bd;
    bd.size = 64;
    bd.usage = rhi::BufferUsage::ShaderRead | rhi::BufferUsage::ShaderWrite | rhi::BufferUsage::IndirectArgs;
    bd.debugName = "test arguments";
    rhi::BufferHandle arguments = td.device->createBuffer(bd);
    const uint32_t args[4] = {1, 1, 1, 2};  // one group; word 3: two rays
    td.device->writeBuffer(arguments, 0, args, sizeof(args));
    bd.usage = rhi::BufferUsage::ShaderRead;
    bd.debugName = "test rays";
    rhi::BufferHandle rays = td.device->createBuffer(bd);
    const uint32_t list[2] = {reflections::packReflectionRay(16, 28), reflections::packReflectionRay(20, 30)};
    td.device->writeBuffer(rays, 0, list, sizeof(list));
    rhi::TextureDesc od;
    od.format = rhi::Format::RGBA16_FLOAT;
    od.width = od.height = 32;
    od.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    od.debugName = "test reflections";
    rhi::TextureHandle out = td.device->createTexture(od);
    td.device->clearTexture(out, 0, 1, rhi::ClearValue{});
    od.width = 16;
    od.debugName = "small reflections";
    rhi::TextureHandle small = td.device->createTexture(od);
    gi::ReflectionRaysDesc good;
    good.rays = rays;
    good.arguments = good.count = arguments;
    good.countOffset = 12;
    good.output = out;
    CHECK_FALSE(context->traceReflectionRays(good));  // before any dispatch
    CHECK(context->lastError().message.find("no dispatch() yet") != std::string::npos);
    frames(td, *r, 8);
    struct Case {
        const char* expect;
        std::function<void(gi::ReflectionRaysDesc&)> spoil;
    };
    const Case cases[] = {
        {"'rays' is missing", [](gi::ReflectionRaysDesc& d) { d.rays = {}; }},
        {"'arguments' (buffer 'test rays') lacks the usage", [&](gi::ReflectionRaysDesc& d) { d.arguments = rays; }},
        {"does not hold 12 bytes at offset 60", [](gi::ReflectionRaysDesc& d) { d.argumentsOffset = 60; }},
        {"does not hold 4 bytes at offset 6", [](gi::ReflectionRaysDesc& d) { d.countOffset = 6; }},
        {"'output' is missing", [](gi::ReflectionRaysDesc& d) { d.output = {}; }},
        {"'output' (texture 'small reflections') is 16x32", [&](gi::ReflectionRaysDesc& d) { d.output = small; }},
    };
    for (const Case& c : cases) {
        gi::ReflectionRaysDesc d = good;
        c.spoil(d);
        CHECK_FALSE(context->traceReflectionRays(d));
        INFO("message: " << context->lastError().message);
        CHECK(context->lastError().message.find(c.expect) != std::string::npos);
    }
    td.device->endFrame();
    for (float v : readRgba16f(td, out, 32, 32)) REQUIRE(v == 0.0f);
    // The good description traces the two listed pixels of the floor: they reflect the lit box (alpha 1, not black);
    // nothing else is written.
    REQUIRE(context->traceReflectionRays(good));
    td.device->endFrame();
    const std::vector<float> texels = readRgba16f(td, out, 32, 32);
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            const float* t = &texels[4 * (size_t(y) * 32 + x)];
            const bool listed = (x == 16 && y == 28) || (x == 20 && y == 30);
            INFO("pixel " << x << "," << y << ": " << t[0] << " " << t[1] << " " << t[2] << " " << t[3]);
            if (listed) {
                CHECK(t[3] == 1.0f);
                CHECK(t[0] + t[1] + t[2] > 0.0f);
            } else {
                CHECK(t[3] == 0.0f);
            }
        }
    for (rhi::TextureHandle t : {out, small}) td.device->destroy(t);
    for (rhi::BufferHandle b : {arguments, rays}) td.device->destroy(b);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("GI's reflection rays trace the listed pixels and reject bad input", "[reflections]", reflectionRaysRejectBadInput)
BACKEND_TEST("Hybrid reflections on a mirror-like floor beat GI's specular against the path tracer", "[reflections]", mirrorFloor)
BACKEND_TEST("Hybrid reflections on a glossy floor beat GI's specular against the path tracer", "[reflections]", glossyFloor)

#if defined(BRICKLIGHT_HAS_VULKAN) && defined(BRICKLIGHT_HAS_GL)
TEST_CASE("Hybrid reflections on Vulkan and GL agree", "[reflections][cross]") {
    // The same 24 frames of the mirror floor on both backends: GI's passes race where threads blend into the same
    // cache texel, so the two differ by noise: relMSE below 0.01 and means within 5 % (measured in the test's INFO).
    const scenes::SceneGeometry scene = scenes::cornellMirror(0.05f);
    render::Image images[2];
    const char* backends[2] = {"vulkan", "gl"};
    for (int i = 0; i < 2; ++i) {
        TestDevice td = makeDevice(backends[i]);
        REQUIRE(td.device);
        auto r = reflectingRenderer(td, scene, render::ReflectionMode::Hybrid);
        frames(td, *r, 24);
        images[i] = r->readReflections();
        REQUIRE_NO_MESSAGES(td);
    }
    const render::ImageMetrics m = render::compareImages(images[1], images[0]);
    INFO("reflections GL vs Vulkan: relMSE " << m.relMse << " means " << m.meanA << " / " << m.meanB);
    CHECK(m.relMse < 0.01);
    CHECK(std::abs(m.meanA - m.meanB) < 0.05 * m.meanB);
}
#endif
