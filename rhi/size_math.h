// Overflow-safe arithmetic on resource sizes, for code that must not trust a description or a range: the
// validation wrapper, the recorder and replayer, the null device and the backends. rhi.h's helpers
// (subresourceBytes, mipExtent) assume a description that has already passed validation; these do not.
#pragma once

#include <cstdint>
#include <optional>

#include "bricklight/rhi.h"

namespace bricklight::rhi::sizes {

// Mips of a full chain down to 1x1(x1) for a largest extent: 1 + floor(log2(extent)); 1 for 0.
// (A width of 2^31 has 32 mips; counting them by shifting until zero would shift by 32.)
uint32_t fullMipCount(uint32_t largestExtent);
// The largest of width and height, and of the depth for a 3D texture.
uint32_t largestExtent(const TextureDesc& desc);
// Extent of `mip` of a dimension of `base` texels: never below 1, and 1 for any mip of 32 or more.
uint32_t mipExtent(uint32_t base, uint32_t mip);

// [offset, offset + size) lies within `total` bytes, without wrapping around.
inline bool rangeInside(uint64_t offset, uint64_t size, uint64_t total) {
    return offset <= total && size <= total - offset;
}

// Bytes one vertex input of `format` reads (0 for a value outside the enum).
uint32_t vertexFormatBytes(VertexFormat format);

// The end (exclusive) of the bytes elements first .. first + count - 1 read from a buffer: element i starts at
// offset + i * stride and reads `elementBytes`; nullopt for count 0 or when the end does not fit 64 bits (a
// first vertex near 2^32 times a large stride).
std::optional<uint64_t> fetchEnd(uint64_t offset, uint64_t first, uint64_t count, uint64_t stride, uint64_t elementBytes);

// Bytes of one subresource as readTexture/writeTexture move them; nullopt when the subresource is outside
// the texture (mip or layers), the format has no size, or the count does not fit 64 bits.
std::optional<uint64_t> subresourceBytes(const TextureDesc& desc, TextureSubresource sub);
// Bytes of every mip of every layer (createTexture's initial data); nullopt when mipLevels is 0 or more than
// a full chain, the format has no size, or the count does not fit 64 bits.
std::optional<uint64_t> textureBytes(const TextureDesc& desc);

}  // namespace bricklight::rhi::sizes
