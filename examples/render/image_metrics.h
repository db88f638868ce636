// Image error metrics for comparing renders (tests and bricklight-compare).
#pragma once

#include "path_tracer.h"

namespace bricklight::render {

constexpr double kRelMseEpsilon = 1e-2;  // relMSE = mean((a - b)^2 / (b^2 + eps)), per channel

struct ImageMetrics {
    double relMse = 0.0;  // against the second image (the reference), epsilon kRelMseEpsilon
    double rmse = 0.0;
    double psnr = 0.0;    // dB, peak 1 (of linear values clamped to [0, 1])
    double meanA = 0.0, meanB = 0.0;
};

// The images must have equal sizes; `mask` (optional, width*height) selects the pixels compared.
ImageMetrics compareImages(const Image& a, const Image& reference, const std::vector<uint8_t>* mask = nullptr);

}  // namespace bricklight::render
