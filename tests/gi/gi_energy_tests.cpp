// Energy accounting for the SDF GI: a closed sphere whose every surface has albedo rho and emits Le (render_test_support.h,
// emittingSphere) has its light in closed form, so the renderer's fast path (direct light + GI) must give, everywhere,
// after one bounce of GI (the lit image fed back holds direct light only) combined = Le (1 + rho + rho²) and GI's
// diffuse output rho Le, and with the feedback (one more bounce per frame) Le / (1 − rho) and rho Le / (1 − rho).
// Most of the sphere is never seen by the camera: its light comes from the field's material (docs/gi.md, "Surfaces
// the camera never saw").
#include "backend_test.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

constexpr float kRho = 0.5f, kLe = 1.0f;

std::unique_ptr<render::RasterRenderer> sphereRenderer(TestDevice& td, bool feedback) {
    render::RasterOptions o;
    o.width = o.height = 48;
    o.gi = true;
    o.giFeedback = feedback;
    std::string error;
    auto r = render::RasterRenderer::create(*td.device, emittingSphere(kRho, kLe), o, &error);
    INFO(error);
    REQUIRE(r);
    return r;
}

double channelMean(const render::Image& img, int c) {
    double s = 0.0;
    for (size_t p = 0; p < size_t(img.width) * img.height; ++p) s += img.rgb[3 * p + size_t(c)];
    return s / double(size_t(img.width) * img.height);
}

void oneBounce(const std::string& backend) {
    // Measured (lavapipe / llvmpipe, 48 frames): GI 0.479–0.487 (96–97.5 %), combined 1.739–1.744. Bounds: 6 % and
    // 3 %. (Before the surfaces no view had lit were lit from the field's material: 0.443, 88.6 %.)
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto r = sphereRenderer(td, false);
    frames(td, *r, 48);
    const double gi = channelMean(r->read(render::Aov::IndirectDiffuse), 0);
    const double combined = channelMean(r->read(render::Aov::Combined), 0);
    INFO("one bounce: GI " << gi << " (expected " << kRho * kLe << "), combined " << combined << " (expected "
                           << kLe * (1 + kRho + kRho * kRho) << ")");
    CHECK(gi == Approx(kRho * kLe).epsilon(0.06));
    CHECK(combined == Approx(kLe * (1 + kRho + kRho * kRho)).epsilon(0.03));
    REQUIRE_NO_MESSAGES(td);
}

void converged(const std::string& backend) {
    // Measured (lavapipe / llvmpipe): GI 0.75 / 0.80 / 0.84 / 0.864–0.868 after 16 / 32 / 64 / 96 frames; it still
    // rises slowly, and settles short of the closed form (docs/notes/gi-quality.md, "Surfaces the camera never
    // saw, and energy in closed form"). Bounds: GI within [0.82, 1.03] of the closed form at 96 frames, combined
    // within 5 %.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto r = sphereRenderer(td, true);
    double gi = 0.0;
    for (uint32_t f : {16u, 32u, 64u, 96u}) {
        frames(td, *r, f - (f == 16u ? 0u : f / 2u));
        gi = channelMean(r->read(render::Aov::IndirectDiffuse), 0);
        UNSCOPED_INFO("frame " << f << ": GI " << gi);
    }
    const double combined = channelMean(r->read(render::Aov::Combined), 0);
    INFO("converged: GI " << gi << " (expected " << kRho * kLe / (1 - kRho) << "), combined " << combined << " (expected "
                          << kLe / (1 - kRho) << ")");
    CHECK(gi > 0.82 * kRho * kLe / (1 - kRho));
    CHECK(gi < 1.03 * kRho * kLe / (1 - kRho));
    CHECK(combined == Approx(kLe / (1 - kRho)).epsilon(0.05));
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("GI energy: one bounce in a closed emitting sphere is Le (1 + rho + rho^2)", "[gi][quick]", oneBounce)
BACKEND_TEST("GI energy: the feedback converges to Le / (1 - rho) in a closed emitting sphere", "[gi]", converged)
