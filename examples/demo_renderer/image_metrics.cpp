#include "image_metrics.h"

#include <algorithm>
#include <cmath>

namespace bricklight::render {

namespace {

double displayLuminance(const Image& img, size_t p) {
    auto curve = [](double x) {
        x = std::max(0.0, x);
        const double t = std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
        return t <= 0.0031308 ? 12.92 * t : 1.055 * std::pow(t, 1.0 / 2.4) - 0.055;
    };
    return 0.2126 * curve(img.rgb[3 * p]) + 0.7152 * curve(img.rgb[3 * p + 1]) + 0.0722 * curve(img.rgb[3 * p + 2]);
}

double meanSsim(const Image& a, const Image& b) {
    const uint32_t w = a.width, h = a.height, window = std::min({8u, w, h});
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    std::vector<double> la(size_t(w) * h), lb(size_t(w) * h);
    for (size_t p = 0; p < la.size(); ++p) la[p] = displayLuminance(a, p), lb[p] = displayLuminance(b, p);
    double sum = 0.0;
    size_t windows = 0;
    const uint32_t step = std::max(1u, window / 2);
    for (uint32_t y = 0; y + window <= h; y += step)
        for (uint32_t x = 0; x + window <= w; x += step) {
            double ma = 0, mb = 0;
            for (uint32_t j = 0; j < window; ++j)
                for (uint32_t i = 0; i < window; ++i) ma += la[size_t(y + j) * w + x + i], mb += lb[size_t(y + j) * w + x + i];
            const double n = double(window) * window;
            ma /= n;
            mb /= n;
            double va = 0, vb = 0, cov = 0;
            for (uint32_t j = 0; j < window; ++j)
                for (uint32_t i = 0; i < window; ++i) {
                    const double da = la[size_t(y + j) * w + x + i] - ma, db = lb[size_t(y + j) * w + x + i] - mb;
                    va += da * da;
                    vb += db * db;
                    cov += da * db;
                }
            va /= n - 1;
            vb /= n - 1;
            cov /= n - 1;
            sum += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            windows++;
        }
    return windows ? sum / double(windows) : 1.0;
}

}  // namespace

double imageGrain(const Image& img) {
    if (img.width < 3 || img.height < 3 || img.rgb.size() != size_t(img.width) * img.height * 3) return 0.0;
    const uint32_t w = img.width, h = img.height;
    std::vector<double> l(size_t(w) * h);
    for (size_t p = 0; p < l.size(); ++p) l[p] = displayLuminance(img, p);
    double sum = 0.0;
    for (uint32_t y = 1; y + 1 < h; ++y)
        for (uint32_t x = 1; x + 1 < w; ++x) {
            const size_t p = size_t(y) * w + x;
            sum += std::abs(4.0 * l[p] - l[p - 1] - l[p + 1] - l[p - w] - l[p + w]);
        }
    return sum / (double(w - 2) * double(h - 2));
}

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
    m.ssim = meanSsim(a, b);
    m.grainA = imageGrain(a);
    m.grainB = imageGrain(b);
    return m;
}

}  // namespace bricklight::render
