// The direct light over frames (raster_renderer_direct_history.cpp): a still camera converges as if each pixel had
// all the frames' samples, a moving camera keeps the history of the points it still sees, and changed lights start
// the mean over. The reference is the same estimator with many samples in one frame (RasterOptions::directFrames 1),
// so that the comparison measures the accumulation alone.
#include "backend_test.h"
#include "image_metrics.h"
#include "raster_renderer.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

constexpr uint32_t kSize = 64;

std::unique_ptr<render::RasterRenderer> directRenderer(TestDevice& td, const scenes::SceneGeometry& scene, uint32_t lightSamples,
                                                       uint32_t directFrames, uint32_t seed = 1) {
    render::RasterOptions ro;
    ro.width = ro.height = kSize;
    ro.lightSamples = lightSamples;
    ro.directFrames = directFrames;
    ro.seed = seed;
    std::string error;
    auto r = render::RasterRenderer::create(*td.device, scene, ro, &error);
    INFO(error);
    REQUIRE(r);
    return r;
}

// 512 samples in one frame, from another seed than the renderers it judges.
render::Image converged(TestDevice& td, const scenes::SceneGeometry& scene) {
    auto r = directRenderer(td, scene, 512, 1, 7);
    frames(td, *r, 1);
    return r->read(render::Aov::Direct);
}

void stillCameraConverges(const std::string& backend) {
    // 4 samples a frame. One frame's error against the converged image is the estimator's noise; 48 frames
    // average it down ~48× (the reference's own noise adds ~1/128 of one frame's). Bound: below 1/10 of one
    // frame's relMSE, the mean within 1 %, and the grain within 10 % of the converged image's.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    const render::Image reference = converged(td, cornell);
    auto r = directRenderer(td, cornell, 4, 1024);
    frames(td, *r, 1);
    const render::ImageMetrics one = render::compareImages(r->read(render::Aov::Direct), reference);
    frames(td, *r, 47);
    const render::ImageMetrics many = render::compareImages(r->read(render::Aov::Direct), reference);
    WARN(backend << ": direct light vs 512 samples: one frame relMSE " << one.relMse << " grain " << one.grainA << "; 48 frames relMSE "
                 << many.relMse << " grain " << many.grainA << " mean " << many.meanA << " vs " << many.meanB << " (grain " << many.grainB << ")");
    CHECK(many.relMse < 0.1 * one.relMse);
    CHECK(many.meanA == Approx(many.meanB).epsilon(0.01));
    CHECK(many.grainA < 1.1 * many.grainB);
    REQUIRE_NO_MESSAGES(td);
}

void movingCameraKeepsItsHistory(const std::string& backend) {
    // The camera slides sideways a little every frame for 24 frames. The points it keeps seeing keep their
    // history, so the image at the last camera is far less noisy than one frame (below 1/3 of one frame's relMSE
    // against 512 samples at that camera), and nothing trails behind: the mean stays within 2 %.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    auto r = directRenderer(td, cornell, 4, 1024);
    const glm::vec3 side = 0.004f * glm::length(cornell.boundsMax - cornell.boundsMin) * glm::vec3(1.0f, 0.0f, 0.0f);
    scenes::Camera camera = cornell.camera;
    std::string error;
    for (int f = 0; f < 24; ++f) {
        camera.eye += side;
        camera.at += side;
        REQUIRE(r->setCamera(camera, &error));
        frames(td, *r, 1);
    }
    const render::Image moved = r->read(render::Aov::Direct);
    scenes::SceneGeometry atEnd = cornell;
    atEnd.camera = camera;
    const render::Image reference = converged(td, atEnd);
    auto single = directRenderer(td, atEnd, 4, 1);
    frames(td, *single, 1);
    const render::ImageMetrics one = render::compareImages(single->read(render::Aov::Direct), reference);
    const render::ImageMetrics m = render::compareImages(moved, reference);
    WARN(backend << ": direct light after 24 moving frames: relMSE " << m.relMse << " (one frame " << one.relMse << "), mean " << m.meanA
                 << " vs " << m.meanB);
    CHECK(m.relMse < one.relMse / 3.0);
    CHECK(m.meanA == Approx(m.meanB).epsilon(0.02));
    REQUIRE_NO_MESSAGES(td);
}

void changedLightsStartOver(const std::string& backend) {
    // After 16 frames, the emitter's emission doubles (setScene). The next frame's direct light must be the new
    // light's alone: twice the old mean within the noise of one frame (5 %), not a mix with the history (a mean
    // kept over even 4 frames would give ~1.25×).
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    scenes::SceneGeometry cornell = scenes::cornellBox();
    auto r = directRenderer(td, cornell, 16, 1024);
    frames(td, *r, 16);
    const double before = imageMean(r->read(render::Aov::Direct));
    for (scenes::TriangleMesh& m : cornell.meshes) m.emission *= 2.0f;
    std::string error;
    REQUIRE(r->setScene(cornell, &error));
    frames(td, *r, 1);
    const double after = imageMean(r->read(render::Aov::Direct));
    WARN(backend << ": direct light mean " << before << " before, " << after << " the frame after the emission doubled");
    CHECK(after == Approx(2.0 * before).epsilon(0.05));
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("direct light: a still camera converges over frames", "[render][quick]", stillCameraConverges)
BACKEND_TEST("direct light: a moving camera keeps the history of the points it still sees", "[render]", movingCameraKeepsItsHistory)
BACKEND_TEST("direct light: changed lights start the mean over", "[render]", changedLightsStartOver)
