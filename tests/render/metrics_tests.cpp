// Image metrics on images whose answers are known by hand.
#include <catch2/catch.hpp>
#include <random>

#include "image_metrics.h"

using namespace bricklight;

namespace {
render::Image constant(uint32_t w, uint32_t h, float v) {
    render::Image img;
    img.width = w;
    img.height = h;
    img.rgb.assign(size_t(w) * h * 3, v);
    return img;
}
}  // namespace

TEST_CASE("metrics: relMSE, RMSE, PSNR of constant images", "[metrics]") {
    const render::ImageMetrics m = render::compareImages(constant(16, 16, 1.1f), constant(16, 16, 1.0f));
    CHECK(m.relMse == Approx(0.01 / (1.0 + render::kRelMseEpsilon)).epsilon(1e-5));
    CHECK(m.rmse == Approx(0.1).epsilon(1e-5));
    CHECK(std::isinf(m.psnr));  // both clamp to 1: no visible difference
    const render::ImageMetrics d = render::compareImages(constant(16, 16, 0.5f), constant(16, 16, 0.4f));
    CHECK(d.psnr == Approx(20.0).epsilon(1e-4));  // 10 log10(1 / 0.01)
    CHECK(render::compareImages(constant(8, 8, 1), constant(4, 4, 1)).relMse == INFINITY);
}

TEST_CASE("metrics: SSIM is 1 for equal images and falls with noise", "[metrics]") {
    render::Image a = constant(32, 32, 0.3f);
    for (uint32_t i = 0; i < a.rgb.size(); ++i) a.rgb[i] = 0.2f + 0.3f * float((i / 3) % 32) / 32.0f;  // a ramp
    CHECK(render::compareImages(a, a).ssim == Approx(1.0));
    std::mt19937 rng(3);
    std::normal_distribution<float> noise(0.0f, 0.05f);
    render::Image noisy = a, noisier = a;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        const float n = noise(rng);
        noisy.rgb[i] += n;
        noisier.rgb[i] += 3 * n;
    }
    const double s1 = render::compareImages(noisy, a).ssim, s3 = render::compareImages(noisier, a).ssim;
    INFO("SSIM " << s1 << " then " << s3);
    CHECK(s1 < 0.99);
    CHECK(s3 < s1);
}
