#include "case_helpers.h"

#include <cmath>

namespace bricklight::conformance {


uint16_t floatToHalf(float f) {
    // Exact for the values the cases use (representable halves); rounds to nearest otherwise.
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    uint32_t sign = (bits >> 16) & 0x8000;
    float a = std::fabs(f);
    if (a == 0.0f) return uint16_t(sign);
    int e;
    float m = std::frexp(a, &e);  // a = m * 2^e, m in [0.5, 1)
    int exp = e + 14;
    if (exp <= 0) return uint16_t(sign | uint32_t(std::lround(std::ldexp(a, 24))));
    if (exp >= 31) return uint16_t(sign | 0x7C00);
    uint32_t mant = uint32_t(std::lround((m * 2.0f - 1.0f) * 1024.0f));
    if (mant == 1024) mant = 0, ++exp;
    return uint16_t(sign | uint32_t(exp) << 10 | mant);
}

namespace {
float smallFloat(uint32_t exp, uint32_t mant, int mantBits) {
    if (exp == 0) return std::ldexp(float(mant), -14 - mantBits);
    if (exp == 31) return mant ? NAN : INFINITY;
    return std::ldexp(float(mant | (1u << mantBits)), int(exp) - 15 - mantBits);
}
}  // namespace

void decodeR11G11B10(uint32_t p, float out[3]) {
    out[0] = smallFloat((p >> 6) & 31, p & 63, 6);
    out[1] = smallFloat((p >> 17) & 31, (p >> 11) & 63, 6);
    out[2] = smallFloat((p >> 27) & 31, (p >> 22) & 31, 5);
}

void decodeRgb9e5(uint32_t p, float out[3]) {
    const int exponent = int(p >> 27) - 15 - 9;
    for (int c = 0; c < 3; ++c) out[c] = std::ldexp(float((p >> (9 * c)) & 511u), exponent);
}

float srgbToLinear(uint8_t v) {
    float c = v / 255.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

void decodeTexel(rhi::Format format, const uint8_t* t, float out[4]) {
    using F = rhi::Format;
    out[0] = out[1] = out[2] = 0.0f;
    out[3] = 1.0f;
    auto f32 = [&](int i) {
        float v;
        std::memcpy(&v, t + 4 * i, 4);
        return v;
    };
    auto h16 = [&](int i) {
        uint16_t v;
        std::memcpy(&v, t + 2 * i, 2);
        return halfToFloat(v);
    };
    switch (format) {
        case F::R8_UNORM: out[0] = t[0] / 255.0f; break;
        case F::RG8_UNORM: out[0] = t[0] / 255.0f, out[1] = t[1] / 255.0f; break;
        case F::RGBA8_UNORM:
            for (int i = 0; i < 4; ++i) out[i] = t[i] / 255.0f;
            break;
        case F::RGBA8_SRGB:
            for (int i = 0; i < 3; ++i) out[i] = srgbToLinear(t[i]);
            out[3] = t[3] / 255.0f;
            break;
        case F::R16_FLOAT: out[0] = h16(0); break;
        case F::RG16_FLOAT: out[0] = h16(0), out[1] = h16(1); break;
        case F::RGBA16_FLOAT:
            for (int i = 0; i < 4; ++i) out[i] = h16(i);
            break;
        case F::R32_FLOAT:
        case F::D32_FLOAT: out[0] = f32(0); break;
        case F::RG32_FLOAT: out[0] = f32(0), out[1] = f32(1); break;
        case F::RGBA32_FLOAT:
            for (int i = 0; i < 4; ++i) out[i] = f32(i);
            break;
        case F::R11G11B10_FLOAT: {
            uint32_t p;
            std::memcpy(&p, t, 4);
            decodeR11G11B10(p, out);
            break;
        }
        case F::RGB9E5_FLOAT: {
            uint32_t p;
            std::memcpy(&p, t, 4);
            decodeRgb9e5(p, out);
            break;
        }
        default: break;
    }
}

std::vector<uint8_t> patternBytes(size_t count, uint32_t seed) {
    std::vector<uint8_t> out(count);
    uint32_t x = seed * 2654435761u + 12345u;
    for (auto& b : out) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        b = uint8_t(x >> 24);
    }
    return out;
}

}  // namespace bricklight::conformance
