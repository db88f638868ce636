// The rasterized path against the path tracer: G-buffer AOVs (albedo, normal, depth) against the path
// tracer's primary-hit AOVs, direct lighting against its direct-only output, motion vectors against the
// cameras, and Vulkan against GL.
#include <glm/gtc/matrix_transform.hpp>

#include "backend_test.h"
#include "image_metrics.h"
#include "path_tracer.h"
#include "raster_renderer.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

void gbufferMatchesPathTracer(const std::string& backend) {
    // The path tracer with camera rays through the pixel centres, as the rasterizer samples: the primary
    // hits are the same surfaces. Tolerances: albedo and normal are stored as 16-bit floats (5e-4
    // relative); depth: the raster's world position is an interpolated varying, the path tracer's an
    // exact intersection (NVIDIA's interpolation differs by up to ~2e-4 relative; llvmpipe by 5e-7):
    // 5e-4 relative. Silhouette pixels may go either way
    // between a rasterizer's coverage rule and a ray's hit test: at most 0.5 % of the pixels.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    Pair p = makePair(td, cornell, 64, 1, 1, false);
    const size_t pixels = 64 * 64;
    struct Check { render::Aov aov; double tolerance; bool relative; };
    for (const Check& c : {Check{render::Aov::Albedo, 1e-3, false}, Check{render::Aov::Normal, 2e-3, false},
                           Check{render::Aov::Depth, 5e-4, true}}) {
        const render::Image r = p.raster->read(c.aov), t = p.tracer->read(c.aov);
        size_t bad = 0;
        double worst = 0.0;
        for (size_t i = 0; i < pixels; ++i)
            for (int k = 0; k < 3; ++k) {
                double e = std::fabs(double(r.rgb[3 * i + size_t(k)]) - t.rgb[3 * i + size_t(k)]);
                if (c.relative) e /= std::max(1e-6, std::fabs(double(t.rgb[3 * i + size_t(k)])));
                if (e > c.tolerance) {
                    bad++;
                    break;
                }
                worst = std::max(worst, e);
            }
        INFO(render::aovName(c.aov) << ": " << bad << " of " << pixels << " pixels differ by more than " << c.tolerance
                                   << "; largest difference elsewhere " << worst);
        CHECK(bad <= pixels / 200);
    }
    REQUIRE_NO_MESSAGES(td);
}

void directMatchesPathTracer(const std::string& backend) {
    // The raster path's direct light (256 light samples per pixel) against the path tracer's direct-only
    // AOV (256 spp, camera rays through pixel centres) at 64 x 64: relMSE below 0.02 and means within 2 %,
    // on the Cornell box (area light) and the atrium (sun and sky).
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    for (const scenes::SceneGeometry& scene : {scenes::cornellBox(), scenes::atrium()}) {
        Pair p = makePair(td, scene, 64, 256, 256, false);
        const render::ImageMetrics m = render::compareImages(p.raster->read(render::Aov::Direct), p.tracer->read(render::Aov::Direct));
        WARN(scene.name << " " << backend << ": rasterized direct vs path-traced direct: relMSE " << m.relMse << ", means " << m.meanA
                        << " / " << m.meanB);
        CHECK(m.relMse < 0.02);
        CHECK(m.meanA == Approx(m.meanB).epsilon(0.02));
    }
    REQUIRE_NO_MESSAGES(td);
}

void motionVectors(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    render::RasterOptions ro;
    ro.width = ro.height = 32;
    ro.lightSamples = 1;
    std::string error;
    auto r = render::RasterRenderer::create(*td.device, cornell, ro, &error);
    REQUIRE(r);
    r->render();
    const render::Image still = r->readMotion();
    double largest = 0.0;
    for (float v : still.rgb) largest = std::max(largest, double(std::fabs(v)));
    CHECK(largest == 0.0);  // the first frame has no previous camera: zero motion
    scenes::Camera moved = cornell.camera;
    moved.eye += glm::vec3(-20.0f, 10.0f, 0.0f);
    moved.at += glm::vec3(-20.0f, 10.0f, 0.0f);
    REQUIRE(r->setCamera(moved, &error));
    r->render();
    const render::Image motion = r->readMotion();
    const render::Image depth = r->read(render::Aov::Depth);
    // Expected: the UV of each pixel's surface point under the new camera minus under the old one.
    const glm::mat4 now = render::viewProjection(moved, 1.0f, 1000.0f), before = render::viewProjection(cornell.camera, 1.0f, 1000.0f);
    const glm::vec3 forward = glm::normalize(moved.at - moved.eye);
    const glm::mat4 inverse = glm::inverse(now);
    double worst = 0.0;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            const float d = depth.at(x, y).x;
            if (d <= 0.0f) continue;
            const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / 32.0f * 2.0f - 1.0f;
            glm::vec4 far = inverse * glm::vec4(ndc, 1.0f, 1.0f);
            const glm::vec3 dir = glm::normalize(glm::vec3(far) / far.w - moved.eye);
            const glm::vec3 p = moved.eye + dir * (d / glm::dot(dir, forward));
            auto uv = [&](const glm::mat4& m) {
                const glm::vec4 c = m * glm::vec4(p, 1.0f);
                return glm::vec2(c) / c.w * 0.5f + 0.5f;
            };
            const glm::vec2 expected = uv(now) - uv(before);
            worst = std::max(worst, double(glm::length(glm::vec2(motion.at(x, y)) - expected)));
        }
    INFO("largest motion vector error " << worst << " (UV units)");
    CHECK(worst < 2e-3);  // 16-bit float storage of values up to ~0.05
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("raster: G-buffer matches the path tracer's primary-hit AOVs", "[render][quick]", gbufferMatchesPathTracer)
BACKEND_TEST("raster: direct lighting matches the path tracer's direct-only output", "[render]", directMatchesPathTracer)
BACKEND_TEST("raster: motion vectors follow the camera", "[render]", motionVectors)

#if defined(BRICKLIGHT_HAS_VULKAN) && defined(BRICKLIGHT_HAS_GL)
TEST_CASE("raster: Vulkan and GL give the same image", "[render][cross]") {
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    auto renderOn = [&](const char* backend) {
        TestDevice td = makeDevice(backend);
        REQUIRE(td.device);
        render::RasterOptions ro;
        ro.width = ro.height = 64;
        std::string error;
        auto r = render::RasterRenderer::create(*td.device, cornell, ro, &error);
        REQUIRE(r);
        r->render();
        render::Image img = r->read(render::Aov::Combined);
        REQUIRE_NO_MESSAGES(td);
        return img;
    };
    const render::ImageMetrics m = render::compareImages(renderOn("vulkan"), renderOn("gl"));
    WARN("raster cornell 64x64, Vulkan vs GL: relMSE " << m.relMse << ", PSNR " << m.psnr << " dB");
    CHECK(m.relMse < 1e-4);
}
#endif
