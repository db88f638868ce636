#include "specular_albedo.h"

#include <algorithm>
#include <cmath>

namespace bricklight::render {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr uint32_t kSamples = 4096;

double radicalInverse(uint32_t bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return double(bits) * (1.0 / 4294967296.0);
}

}  // namespace

std::vector<float> specularAlbedoTable() {
    std::vector<float> table(2u * kSpecularAlbedoSize * kSpecularAlbedoSize);
    for (uint32_t y = 0; y < kSpecularAlbedoSize; ++y)
        for (uint32_t x = 0; x < kSpecularAlbedoSize; ++x) {
            const double nv = (x + 0.5) / kSpecularAlbedoSize, roughness = (y + 0.5) / kSpecularAlbedoSize;
            // As evalBrdf: α = max(roughness², 1e-3).
            const double alpha = std::max(roughness * roughness, 1e-3), a2 = alpha * alpha;
            const double vx = std::sqrt(1.0 - nv * nv), vz = nv;  // the view in the tangent frame (y = 0)
            double a = 0.0, b = 0.0;
            // Half vectors drawn from D(h) (n·h): the estimator of ∫ D V F (n·l) dl is 4 V (n·l)(v·h) / (n·h) · F.
            for (uint32_t i = 0; i < kSamples; ++i) {
                const double u1 = (i + 0.5) / kSamples, u2 = radicalInverse(i);
                const double cosTheta = std::sqrt((1.0 - u1) / (1.0 + (a2 - 1.0) * u1));
                const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta)), phi = 2.0 * kPi * u2;
                const double hx = sinTheta * std::cos(phi), hz = cosTheta;
                const double vh = vx * hx + vz * hz;
                if (vh <= 0.0) continue;
                const double nl = 2.0 * vh * hz - vz;
                if (nl <= 0.0) continue;
                const double visibility =
                    0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
                const double weight = 4.0 * visibility * nl * vh / hz;
                const double fresnel = std::pow(1.0 - vh, 5.0);
                a += weight * (1.0 - fresnel);
                b += weight * fresnel;
            }
            const size_t texel = size_t(y) * kSpecularAlbedoSize + x;
            table[2 * texel] = float(a / kSamples);
            table[2 * texel + 1] = float(b / kSamples);
        }
    return table;
}

}  // namespace bricklight::render
