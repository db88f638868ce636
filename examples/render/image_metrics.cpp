#include "image_metrics.h"

#include <algorithm>
#include <cmath>

namespace bricklight::render {

ImageMetrics compareImages(const Image& a, const Image& b, const std::vector<uint8_t>* mask) {
    ImageMetrics m;
    if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size()) {
        m.relMse = m.rmse = INFINITY;
        return m;
    }
    double rel = 0.0, se = 0.0, clampedSe = 0.0, sumA = 0.0, sumB = 0.0;
    size_t n = 0;
    for (size_t p = 0; p < size_t(a.width) * a.height; ++p) {
        if (mask && !(*mask)[p]) continue;
        for (int c = 0; c < 3; ++c) {
            const double x = a.rgb[3 * p + size_t(c)], y = b.rgb[3 * p + size_t(c)];
            rel += (x - y) * (x - y) / (y * y + kRelMseEpsilon);
            se += (x - y) * (x - y);
            const double cx = std::clamp(x, 0.0, 1.0), cy = std::clamp(y, 0.0, 1.0);
            clampedSe += (cx - cy) * (cx - cy);
            sumA += x;
            sumB += y;
            n++;
        }
    }
    if (!n) return m;
    m.relMse = rel / double(n);
    m.rmse = std::sqrt(se / double(n));
    const double mse = clampedSe / double(n);
    m.psnr = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : INFINITY;
    m.meanA = sumA / double(n);
    m.meanB = sumB / double(n);
    return m;
}

}  // namespace bricklight::render
