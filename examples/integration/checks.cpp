#include "checks.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "bricklight/half.h"  // halfToFloat, for RGBA16_FLOAT read-backs

namespace integration {

using namespace bricklight;

namespace {

// The tolerances, with the reasons behind them.
// GI must light what the sun does not reach: the mean indirect radiance of the pixels in shadow, relative
// to the mean direct radiance of the sunlit ones. By energy, the flux that the sun patch (~2 m²) reflects,
// spread over the ~66 m² inside the room, gives surfaces of albedo ~0.7 a first bounce of about
// 0.7 * 2 / 66 ≈ 2 % of the patch's radiance; each fed-back frame adds a further bounce (measured: 3.5 %
// after 24 frames, 3.7 % after 32, 4.1 % after 64, the same on both backends). We ask for at least
// three quarters of the one-bounce estimate, and at most several times it (more would be light from nowhere).
constexpr float kMinShadowedToSunlit = 0.015f;
constexpr float kMaxShadowedToSunlit = 0.15f;
// Nearly every shadowed pixel gets some GI (the room is closed but for its front).
constexpr float kMinShadowedWithGi = 0.95f;
// Sun visibility through the field agrees with exact ray-box tests except along shadow edges, where a
// voxel-sized field differs from the exact boxes.
constexpr float kMinShadowAgreement = 0.95f;
// The sun patch must be there: some pixels sunlit, most not.
constexpr float kMinSunlitFraction = 0.01f, kMaxSunlitFraction = 0.5f;

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
bool finite(const glm::vec4& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w); }

std::vector<glm::vec4> readHalf4(rhi::IDevice& device, rhi::TextureHandle t, size_t pixels) {
    std::vector<uint16_t> h(pixels * 4);
    std::vector<glm::vec4> out(pixels, glm::vec4(NAN));
    if (!device.readTexture(t, {}, h.data())) return out;
    for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 4; ++c) out[i][c] = halfToFloat(h[4 * i + size_t(c)]);
    return out;
}

}  // namespace

bool reportCheck(bool ok, const std::string& what) {
    printf("  check %-64s %s\n", what.c_str(), ok ? "ok" : "FAILED");
    return ok;
}

bool checkFrame(rhi::IDevice& device, const FrameImages& images, const CheckInputs& in) {
    const size_t pixels = size_t(in.width) * in.height;
    std::vector<float> depth(pixels, 1.0f);
    std::vector<uint8_t> albedo8(pixels * 4);
    device.readTexture(images.depth, {}, depth.data());
    device.readTexture(images.albedo, {}, albedo8.data());
    const std::vector<glm::vec4> normal = readHalf4(device, images.normal, pixels);
    const std::vector<glm::vec4> giDiffuse = readHalf4(device, images.giDiffuse, pixels);
    const std::vector<glm::vec4> giSpecular = readHalf4(device, images.giSpecular, pixels);
    const std::vector<glm::vec4> lit = readHalf4(device, images.lit, pixels);
    const std::vector<glm::vec4> direct = readHalf4(device, images.direct, pixels);

    const glm::mat4 inverseViewProjection = glm::inverse(in.viewProjection);
    const glm::vec3 toSun = in.room->sun.direction;
    size_t geometry = 0, nonFinite = 0, sunlit = 0, shadowed = 0, shadowedWithGi = 0, facingSun = 0, agree = 0;
    size_t floorPixels = 0, ceilingPixels = 0;
    double floorRows = 0.0, ceilingRows = 0.0;  // to tell an upright image from an upside-down one
    double sunlitDirect = 0.0, shadowedIndirect = 0.0, shadowedLit = 0.0, shadowedDirect = 0.0;
    for (size_t i = 0; i < pixels; ++i) {
        if (!finite(lit[i]) || !finite(giDiffuse[i]) || !finite(giSpecular[i]) || !finite(direct[i])) ++nonFinite;
        if (!(depth[i] < 1.0f)) continue;
        ++geometry;
        const glm::vec3 albedo = glm::vec3(albedo8[4 * i], albedo8[4 * i + 1], albedo8[4 * i + 2]) / 255.0f;
        const glm::vec3 n = glm::normalize(glm::vec3(normal[i]));
        if (n.y > 0.9f) ++floorPixels, floorRows += double(i / in.width);
        if (n.y < -0.9f) ++ceilingPixels, ceilingRows += double(i / in.width);
        const bool litBySun = glm::dot(n, toSun) > 0.0f && direct[i].a > 0.5f;
        if (litBySun) {
            ++sunlit;
            sunlitDirect += luminance(glm::vec3(direct[i]));
        } else {
            ++shadowed;
            const float indirect = luminance(albedo * glm::vec3(giDiffuse[i]));
            shadowedIndirect += indirect;
            shadowedLit += luminance(glm::vec3(lit[i]));
            shadowedDirect += luminance(glm::vec3(direct[i]));
            if (luminance(glm::vec3(giDiffuse[i])) > 0.0f) ++shadowedWithGi;
        }
        // The same shadow ray on the CPU, against the boxes themselves: the pixel's position rebuilt from
        // depth exactly as the composite does it (a y-flip or depth-range mistake shows up here).
        if (glm::dot(n, toSun) > 0.0f) {
            const uint32_t x = uint32_t(i % in.width), y = uint32_t(i / in.width);
            const glm::vec2 ndc = (glm::vec2(float(x), float(y)) + 0.5f) / glm::vec2(float(in.width), float(in.height)) * 2.0f - 1.0f;
            const glm::vec4 w = inverseViewProjection * glm::vec4(ndc, depth[i], 1.0f);
            const glm::vec3 origin = glm::vec3(w) / w.w + n * in.shadowRayOffset;
            const bool exactlyLit = !rayHitsAnyBox(*in.room, origin, toSun);
            ++facingSun;
            if (exactlyLit == (direct[i].a > 0.5f)) ++agree;
        }
    }
    const double meanSunlit = sunlit ? sunlitDirect / double(sunlit) : 0.0;
    const double meanShadowedIndirect = shadowed ? shadowedIndirect / double(shadowed) : 0.0;
    const double ratio = meanSunlit > 0.0 ? meanShadowedIndirect / meanSunlit : 0.0;
    const double sunlitFraction = geometry ? double(sunlit) / double(geometry) : 0.0;
    const double withGi = shadowed ? double(shadowedWithGi) / double(shadowed) : 0.0;
    const double agreement = facingSun ? double(agree) / double(facingSun) : 0.0;

    printf("figures:\n");
    printf("  pixels with geometry                 %zu of %zu (sunlit %zu, in shadow %zu)\n", geometry, pixels, sunlit, shadowed);
    printf("  mean direct radiance, sunlit         %.4f\n", meanSunlit);
    printf("  mean direct radiance, in shadow      %.4f\n", shadowed ? shadowedDirect / double(shadowed) : 0.0);
    printf("  mean GI radiance (albedo x diffuse GI), in shadow  %.4f  (%.1f %% of sunlit direct)\n", meanShadowedIndirect, 100.0 * ratio);
    printf("  mean lit radiance, in shadow         %.4f  (direct light alone: 0)\n", shadowed ? shadowedLit / double(shadowed) : 0.0);
    printf("  in-shadow pixels with GI > 0         %.1f %%\n", 100.0 * withGi);
    printf("  sun visibility agrees with exact ray-box tests  %.1f %% of %zu pixels facing the sun\n", 100.0 * agreement, facingSun);
    printf("  non-finite pixels                    %zu\n", nonFinite);
    const double floorRow = floorPixels ? floorRows / double(floorPixels) : 0.0;
    const double ceilingRow = ceilingPixels ? ceilingRows / double(ceilingPixels) : 0.0;
    printf("  mean image row of up-facing / down-facing surfaces  %.1f / %.1f (row 0 is the top)\n", floorRow, ceilingRow);

    bool ok = true;
    ok &= reportCheck(nonFinite == 0, "no NaN/inf in lit, direct and GI images");
    // Without the projection's y-flip everything still agrees with everything (same matrices throughout),
    // but the image comes out upside down: the floor must be below the ceiling.
    ok &= reportCheck(floorPixels > 0 && ceilingPixels > 0 && floorRow > ceilingRow, "upright: the floor is drawn below the ceiling");
    ok &= reportCheck(sunlitFraction >= kMinSunlitFraction && sunlitFraction <= kMaxSunlitFraction,
                 "sunlit fraction of the geometry in [1 %, 50 %]");
    ok &= reportCheck(agreement >= kMinShadowAgreement, "shadows traced through the field agree with exact tests >= 95 %");
    ok &= reportCheck(ratio >= kMinShadowedToSunlit, "GI in shadow >= 1.5 % of the sunlit direct radiance");
    ok &= reportCheck(ratio <= kMaxShadowedToSunlit, "GI in shadow <= 15 % of the sunlit direct radiance");
    ok &= reportCheck(withGi >= kMinShadowedWithGi, "GI > 0 on >= 95 % of the pixels in shadow");
    return ok;
}

bool writeLitImage(rhi::IDevice& device, const FrameImages& images, uint32_t width, uint32_t height, const std::string& path) {
    const size_t pixels = size_t(width) * height;
    const std::vector<glm::vec4> lit = readHalf4(device, images.lit, pixels);
    FILE* f = fopen(path.c_str(), "wb");
    if (!f) return false;
    const bool pfm = path.size() >= 4 && path.compare(path.size() - 4, 4, ".pfm") == 0;
    if (pfm) {
        fprintf(f, "PF\n%u %u\n-1.0\n", width, height);  // negative scale: little-endian floats
        for (uint32_t y = height; y-- > 0;)              // PFM rows go bottom to top
            for (uint32_t x = 0; x < width; ++x) fwrite(&lit[size_t(y) * width + x], sizeof(float), 3, f);
    } else {
        fprintf(f, "P6\n%u %u\n255\n", width, height);
        for (const glm::vec4& c : lit)
            for (int k = 0; k < 3; ++k) {
                const float v = std::isfinite(c[k]) ? std::max(c[k], 0.0f) : 0.0f;
                fputc(int(std::lround(255.0f * std::pow(v / (1.0f + v), 1.0f / 2.2f))), f);
            }
    }
    return fclose(f) == 0;
}

}  // namespace integration
