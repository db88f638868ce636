// Image error metrics for comparing renders (tests and bricklight-compare).
#pragma once

#include "path_tracer.h"

namespace bricklight::render {

constexpr double kRelMseEpsilon = 1e-2;  // relMSE = mean((a - b)^2 / (b^2 + eps)), per channel

struct ImageMetrics {
    double relMse = 0.0;  // against the second image (the reference), epsilon kRelMseEpsilon
    double rmse = 0.0;
    double psnr = 0.0;    // dB, peak 1 (of linear values clamped to [0, 1])
    double ssim = 1.0;    // mean SSIM of display luminance (see below)
    double meanA = 0.0, meanB = 0.0;
    double grainA = 0.0, grainB = 0.0;  // imageGrain of each (whole images)
};

// Grain: the mean absolute Laplacian (4 neighbours) of display luminance over the interior pixels. Noise raises
// it, edges and texture set its floor: compare it with a converged reference's (the ratio), not with zero.
double imageGrain(const Image& img);

// The images must have equal sizes; `mask` (optional, width*height) selects the pixels compared (SSIM is
// always over the whole image).
//
// The perceptual measure is SSIM (Wang et al. 2004: 8x8 windows, C1 = 0.01^2, C2 = 0.03^2) on the
// luminance of the display image (the PNG transform: ACES filmic curve, sRGB). Chosen over FLIP for now
// because it is short, well understood and enough to rank noise and bias in GI against a reference; FLIP
// (which models viewing distance and colour) is the planned replacement.
ImageMetrics compareImages(const Image& a, const Image& reference, const std::vector<uint8_t>* mask = nullptr);

}  // namespace bricklight::render
