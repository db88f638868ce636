// Each format's round trip: initial data and writeTexture/readTexture return the same bytes, and a
// shader's texelFetch decodes them as the CPU reference does (unorm, sRGB, half, packed float, integer).
#include <cmath>

#include "case_helpers.h"

namespace bricklight::conformance {
namespace {

using rhi::Format;
constexpr uint32_t kW = 8, kH = 4;

// Texel data that every format stores exactly: finite floats, no denormals, depth in [0, 1].
std::vector<uint8_t> formatData(Format f, uint32_t seed) {
    const auto& info = rhi::formatInfo(f);
    std::vector<uint8_t> bytes = patternBytes(size_t(kW) * kH * info.bytesPerTexel, seed);
    size_t texels = size_t(kW) * kH;
    auto quantFloat = [](uint8_t a, uint8_t b) { return (int(a) - 128) * 0.75f + b / 256.0f; };
    switch (f) {
        case Format::R32_FLOAT:
        case Format::RG32_FLOAT:
        case Format::RGBA32_FLOAT:
            for (size_t i = 0; i + 4 <= bytes.size(); i += 4) {
                float v = quantFloat(bytes[i], bytes[i + 1]);
                std::memcpy(&bytes[i], &v, 4);
            }
            break;
        case Format::D32_FLOAT:
            for (size_t i = 0; i + 4 <= bytes.size(); i += 4) {
                float v = (bytes[i] * 256 + bytes[i + 1]) / 65535.0f;
                std::memcpy(&bytes[i], &v, 4);
            }
            break;
        case Format::R16_FLOAT:
        case Format::RG16_FLOAT:
        case Format::RGBA16_FLOAT:
            for (size_t i = 0; i + 2 <= bytes.size(); i += 2) {
                uint16_t h = floatToHalf(quantFloat(bytes[i], bytes[i + 1] & 0xF0));
                std::memcpy(&bytes[i], &h, 2);
            }
            break;
        case Format::R11G11B10_FLOAT:
            for (size_t t = 0; t < texels; ++t) {
                uint8_t* p = &bytes[t * 4];
                uint32_t r = (1 + p[0] % 29) << 6 | (p[1] & 63), g = (1 + p[2] % 29) << 6 | (p[3] & 63),
                         b = (1 + p[1] % 29) << 5 | (p[0] & 31);
                uint32_t packed = r | g << 11 | b << 22;
                std::memcpy(p, &packed, 4);
            }
            break;
        case Format::RGB9E5_FLOAT:  // every exponent but 31 (GL and Vulkan agree on all of them)
            for (size_t t = 0; t < texels; ++t) {
                uint8_t* p = &bytes[t * 4];
                uint32_t packed = uint32_t(p[0] | p[1] << 8 | p[2] << 16 | (p[3] & 7) << 24) | uint32_t(p[3] % 31) << 27;
                std::memcpy(p, &packed, 4);
            }
            break;
        default: break;
    }
    return bytes;
}

void formatRoundTrip(CaseContext& ctx, Format f) {
    const auto& info = rhi::formatInfo(f);
    const bool depth = info.kind == rhi::FormatInfo::Kind::Depth;
    std::vector<uint8_t> initial = formatData(f, 1 + uint32_t(f));
    std::vector<uint8_t> written = formatData(f, 100 + uint32_t(f));
    rhi::TextureDesc d = texture2D(f, kW, kH, rhi::TextureUsage::Sampled, rhi::formatName(f));
    rhi::TextureHandle tex = ctx.texture(d, initial.data());
    if (!tex) return;
    ctx.check(ctx.readTexture(tex) == initial, std::string(info.name) + ": initial data did not read back unchanged");
    ctx.check(ctx.device.writeTexture(tex, {}, written.data()), "writeTexture failed");
    std::vector<uint8_t> back = ctx.readTexture(tex);
    ctx.check(back == written, std::string(info.name) + ": writeTexture data did not read back unchanged");
    ctx.output("readback", back);

    // texelFetch through a shader of the format's scalar type.
    const bool isUint = info.kind == rhi::FormatInfo::Kind::Uint, isSint = info.kind == rhi::FormatInfo::Kind::Sint;
    rhi::ShaderHandle sh = ctx.shader(isUint ? "rhi_tests/fetch_uint.comp"
                                      : isSint ? "rhi_tests/fetch_sint.comp"
                                               : "rhi_tests/fetch_float.comp");
    rhi::SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = rhi::Filter::Nearest;
    sd.debugName = "nearest";
    rhi::SamplerHandle samp = ctx.sampler(sd);
    rhi::BufferHandle out = ctx.buffer(kW * kH * 16, kStorageUsage, nullptr, "fetched");
    struct { int32_t w, h, lod; } params{int32_t(kW), int32_t(kH), 0};
    rhi::DispatchState s;
    s.shader = sh;
    s.label = "fetch";
    s.bindings.constants.push(rhi::constants(0, params));
    s.bindings.textures.push({0, rhi::wholeTexture(tex), samp});
    s.bindings.storageBuffers.push({0, out, {}, rhi::Access::Write});
    ctx.check(ctx.device.dispatch(s, 1, 1, 1), "dispatch failed");
    if (isUint || isSint) {
        auto got = ctx.read<uint32_t>(out, kW * kH * 4);
        for (uint32_t t = 0; t < kW * kH; ++t) {
            uint32_t expect[4] = {0, 0, 0, 1};
            for (uint32_t c = 0; c < info.channels; ++c) {
                const uint8_t* p = &written[t * info.bytesPerTexel];
                uint32_t comp = info.bytesPerTexel / info.channels;
                uint32_t v = 0;
                std::memcpy(&v, p + c * comp, comp);
                expect[c] = v;
            }
            for (int c = 0; c < 4; ++c)
                if (!ctx.check(got[t * 4 + c] == expect[c], std::string(info.name) + ": texel " + std::to_string(t) +
                                                               " channel " + std::to_string(c) + " fetched " +
                                                               std::to_string(got[t * 4 + c]) + ", expected " +
                                                               std::to_string(expect[c])))
                    return;
        }
        ctx.output("fetched", bytesOf(got));
    } else {
        auto got = ctx.read<float>(out, kW * kH * 4);
        // sRGB decode may use the GPU's approximation; everything else is exact.
        const float tol = f == Format::RGBA8_SRGB ? 2e-3f : 1e-6f;
        for (uint32_t t = 0; t < kW * kH; ++t) {
            float expect[4];
            decodeTexel(f, &written[t * info.bytesPerTexel], expect);
            if (depth) expect[1] = expect[2] = 0.0f, expect[3] = 1.0f;
            for (int c = 0; c < 4; ++c)
                if (!ctx.check(std::fabs(got[t * 4 + c] - expect[c]) <= tol * std::max(1.0f, std::fabs(expect[c])),
                               std::string(info.name) + ": texel " + std::to_string(t) + " channel " +
                                   std::to_string(c) + " fetched " + std::to_string(got[t * 4 + c]) + ", expected " +
                                   std::to_string(expect[c])))
                    return;
        }
        ctx.output("fetched", bytesOf(got), {Tolerance::Kind::Float32, tol});
    }
}

// One case per format, named format_<FORMAT>.
template <Format F>
void formatCase(CaseContext& ctx) {
    formatRoundTrip(ctx, F);
}
#define FORMAT_CASE(F) \
    Case{"format_" #F, "createTexture initialData, writeTexture, readTexture, texelFetch of " #F, formatCase<Format::F>}

}  // namespace

void appendFormatCases(std::vector<Case>& out) {
    out.insert(out.end(), {
        FORMAT_CASE(R8_UNORM),
        FORMAT_CASE(R8_UINT),
        FORMAT_CASE(R16_FLOAT),
        FORMAT_CASE(R16_UINT),
        FORMAT_CASE(R32_FLOAT),
        FORMAT_CASE(R32_UINT),
        FORMAT_CASE(R32_SINT),
        FORMAT_CASE(RG8_UNORM),
        FORMAT_CASE(RG16_FLOAT),
        FORMAT_CASE(RG32_FLOAT),
        FORMAT_CASE(RG32_UINT),
        FORMAT_CASE(RGBA8_UNORM),
        FORMAT_CASE(RGBA8_SRGB),
        FORMAT_CASE(RGBA16_FLOAT),
        FORMAT_CASE(RGBA32_FLOAT),
        FORMAT_CASE(RGBA32_UINT),
        FORMAT_CASE(R11G11B10_FLOAT),
        FORMAT_CASE(RGB9E5_FLOAT),
        FORMAT_CASE(D32_FLOAT),
    });
}
#undef FORMAT_CASE

}  // namespace bricklight::conformance
