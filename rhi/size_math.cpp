#include "size_math.h"

#include <algorithm>
#include <bit>

namespace bricklight::rhi::sizes {

namespace {
// a * b, or nullopt when it does not fit 64 bits.
std::optional<uint64_t> multiply(uint64_t a, uint64_t b) {
    uint64_t r;
    if (__builtin_mul_overflow(a, b, &r)) return std::nullopt;
    return r;
}

bool layered(const TextureDesc& d) {
    return d.dimension == TextureDimension::Texture2DArray || d.dimension == TextureDimension::TextureCube;
}

// Bytes of one layer of one mip (all slices of a 3D mip).
std::optional<uint64_t> layerBytes(const TextureDesc& d, uint32_t mip) {
    const uint32_t depth = d.dimension == TextureDimension::Texture3D ? mipExtent(d.depthOrLayers, mip) : 1;
    auto texels = multiply(mipExtent(d.width, mip), mipExtent(d.height, mip));
    if (texels) texels = multiply(*texels, depth);
    if (!texels) return std::nullopt;
    return multiply(*texels, formatInfo(d.format).bytesPerTexel);
}
}  // namespace

uint32_t fullMipCount(uint32_t largestExtent) { return largestExtent ? uint32_t(std::bit_width(largestExtent)) : 1; }

uint32_t largestExtent(const TextureDesc& d) {
    const uint32_t e = std::max(d.width, d.height);
    return d.dimension == TextureDimension::Texture3D ? std::max(e, d.depthOrLayers) : e;
}

uint32_t mipExtent(uint32_t base, uint32_t mip) {
    const uint32_t e = mip < 32 ? base >> mip : 0;
    return e ? e : 1;
}

std::optional<uint64_t> subresourceBytes(const TextureDesc& d, TextureSubresource sub) {
    if (formatInfo(d.format).bytesPerTexel == 0 || sub.mip >= d.mipLevels) return std::nullopt;
    uint32_t layers = 1;
    if (layered(d)) {
        if (sub.layer >= d.depthOrLayers) return std::nullopt;
        const uint32_t remaining = d.depthOrLayers - sub.layer;
        if (sub.layerCount > remaining) return std::nullopt;
        layers = sub.layerCount ? sub.layerCount : remaining;
    }
    auto bytes = layerBytes(d, sub.mip);
    return bytes ? multiply(*bytes, layers) : std::nullopt;
}

std::optional<uint64_t> textureBytes(const TextureDesc& d) {
    if (formatInfo(d.format).bytesPerTexel == 0 || d.mipLevels == 0 || d.mipLevels > fullMipCount(largestExtent(d)))
        return std::nullopt;
    uint64_t perLayer = 0;
    for (uint32_t mip = 0; mip < d.mipLevels; ++mip) {  // at most 32 iterations (checked above)
        auto bytes = layerBytes(d, mip);
        if (!bytes || __builtin_add_overflow(perLayer, *bytes, &perLayer)) return std::nullopt;
    }
    return multiply(perLayer, layered(d) ? d.depthOrLayers : 1);
}

uint32_t vertexFormatBytes(VertexFormat format) {
    switch (format) {
        case VertexFormat::Float1: return 4;
        case VertexFormat::Float2: return 8;
        case VertexFormat::Float3: return 12;
        case VertexFormat::Float4: return 16;
        case VertexFormat::UByte4Norm: return 4;
        case VertexFormat::UInt1: return 4;
        case VertexFormat::Half4: return 8;
    }
    return 0;
}

std::optional<uint64_t> fetchEnd(uint64_t offset, uint64_t first, uint64_t count, uint64_t stride, uint64_t elementBytes) {
    if (count == 0) return std::nullopt;
    uint64_t last, start, end;
    if (__builtin_add_overflow(first, count - 1, &last) || __builtin_mul_overflow(last, stride, &start) ||
        __builtin_add_overflow(start, offset, &start) || __builtin_add_overflow(start, elementBytes, &end))
        return std::nullopt;
    return end;
}

}  // namespace bricklight::rhi::sizes
