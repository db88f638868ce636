// Shared by the foliage tests (issue 22): the grass pixels of the foliage scene, the error of a mean, and the
// frame-to-frame change of converged indirect light, for comparing a GI technique's ways with alpha-tested cards
// (RasterOptions::foliage) against the path tracer.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "image_metrics.h"
#include "raster_renderer.h"
#include "render_test_support.h"

namespace bricklight::testing {

// Foliage in an albedo image: the cards' texture colour is green-dominant; the ground (brown), the wall (grey),
// the trunk and the sky (0) are not.
inline bool isFoliage(const glm::vec3& albedo) {
    return albedo.g > 1.3f * albedo.r && albedo.g > 1.3f * albedo.b && albedo.g > 0.01f;
}

// The grass pixels of a view of the foliage scene: the foliage pixels of the bottom quarter (the meadow in front
// of the camera), from an albedo image (the path tracer's or the G-buffer's). Returns the mask, width*height.
inline std::vector<uint8_t> grassMask(const render::Image& albedo, size_t* count = nullptr) {
    std::vector<uint8_t> mask(size_t(albedo.width) * albedo.height, 0);
    size_t n = 0;
    for (uint32_t y = albedo.height * 3 / 4; y < albedo.height; ++y)
        for (uint32_t x = 0; x < albedo.width; ++x) n += mask[size_t(y) * albedo.width + x] = isFoliage(albedo.at(x, y));
    if (count) *count = n;
    return mask;
}

// |mean / reference mean − 1|.
inline double meanError(const render::ImageMetrics& m) { return std::fabs(m.meanA / m.meanB - 1.0); }

// The largest frame-to-frame change of the masked pixels' indirect light over `n` more frames: the mean absolute
// difference over the mean.
inline double flicker(TestDevice& td, render::RasterRenderer& r, const std::vector<uint8_t>& mask, uint32_t n) {
    render::Image last = r.read(render::Aov::IndirectDiffuse);
    double worst = 0.0;
    for (uint32_t f = 0; f < n; ++f) {
        frames(td, r, 1);
        const render::Image now = r.read(render::Aov::IndirectDiffuse);
        double diff = 0.0, sum = 0.0;
        for (size_t p = 0; p < mask.size(); ++p)
            if (mask[p])
                for (int c = 0; c < 3; ++c) {
                    diff += std::fabs(now.rgb[3 * p + size_t(c)] - last.rgb[3 * p + size_t(c)]);
                    sum += now.rgb[3 * p + size_t(c)];
                }
        worst = std::max(worst, sum > 0.0 ? diff / sum : 0.0);
        last = now;
    }
    return worst;
}

// The foliage scene in its own light (the sun behind the camera: the camera sees the cards' lit sides) or with the
// sun turned round (behind the cards: their lit sides face away).
inline scenes::SceneGeometry foliageScene(bool sunBehindCards) {
    scenes::SceneGeometry s = scenes::foliage();
    if (sunBehindCards) {
        s.environment.sunDirection.x = -s.environment.sunDirection.x;
        s.environment.sunDirection.z = -s.environment.sunDirection.z;
    }
    return s;
}

// One GI technique's three ways with the cards against a reference's indirect diffuse.
struct FoliageFigures {
    render::ImageMetrics whole, grass;
    double flicker = -1.0;  // frame-to-frame change of the grass after convergence, where measured
};
constexpr render::FoliageMode kFoliageModes[3] = {render::FoliageMode::AlphaAware, render::FoliageMode::Opaque, render::FoliageMode::LeftOut};
constexpr const char* kFoliageModeNames[3] = {"alpha-aware", "opaque", "left out"};

// Renders `s` with `options` in each of kFoliageModes for `frames` frames and compares the indirect diffuse with
// `reference`, over the whole image and the `grass` mask; for the modes whose bit is set in `flickerModes`, the
// frame-to-frame change over `flickerFrames` more frames. The figures are printed (WARN) after `label`.
inline void foliageVariants(TestDevice& td, const scenes::SceneGeometry& s, render::RasterOptions options, uint32_t frameCount,
                            const render::Image& reference, const std::vector<uint8_t>& grass, unsigned flickerModes,
                            uint32_t flickerFrames, const std::string& label, FoliageFigures figures[3]) {
    size_t grassPixels = 0;
    for (uint8_t g : grass) grassPixels += g;
    for (int k = 0; k < 3; ++k) {
        options.foliage = kFoliageModes[k];
        std::string error;
        auto r = render::RasterRenderer::create(*td.device, s, options, &error);
        INFO(error);
        REQUIRE(r);
        frames(td, *r, frameCount);
        const render::Image indirect = r->read(render::Aov::IndirectDiffuse);
        REQUIRE(allFinite(indirect.rgb));
        FoliageFigures& f = figures[k];
        f = {render::compareImages(indirect, reference), render::compareImages(indirect, reference, &grass)};
        if (flickerModes & (1u << k)) f.flicker = flicker(td, *r, grass, flickerFrames);
        WARN(label << ", " << kFoliageModeNames[k] << ": whole relMSE " << f.whole.relMse << " mean " << f.whole.meanA << " vs "
                   << f.whole.meanB << "; grass (" << grassPixels << " pixels) relMSE " << f.grass.relMse << " mean " << f.grass.meanA
                   << " vs " << f.grass.meanB << (f.flicker >= 0.0 ? "; frame-to-frame change " + std::to_string(f.flicker) : ""));
    }
}

}  // namespace bricklight::testing
