// Small helpers shared by the conformance cases: CPU decoding of formats, byte views, record shortcuts.
#pragma once

#include <cstring>
#include <vector>

#include "bricklight/conformance.h"
#include "bricklight/half.h"

namespace bricklight::conformance {

using bricklight::halfToFloat;
uint16_t floatToHalf(float f);
// Decodes an R11G11B10_FLOAT texel to three floats.
void decodeR11G11B10(uint32_t packed, float out[3]);
float srgbToLinear(uint8_t v);
// Decodes one texel of any colour format to the vec4 that a shader's texelFetch returns (missing
// channels read as 0, alpha as 1).
void decodeTexel(rhi::Format format, const uint8_t* texel, float out[4]);

template <typename T>
std::vector<uint8_t> bytesOf(const std::vector<T>& v) {
    std::vector<uint8_t> b(v.size() * sizeof(T));
    if (!b.empty()) std::memcpy(b.data(), v.data(), b.size());
    return b;
}

// A deterministic pseudo-random byte pattern (xorshift), so every case's data is reproducible.
std::vector<uint8_t> patternBytes(size_t count, uint32_t seed);

// Buffer usage for outputs of compute cases.
constexpr uint32_t kStorageUsage = rhi::BufferUsage::ShaderRead | rhi::BufferUsage::ShaderWrite;

inline rhi::TextureDesc texture2D(rhi::Format f, uint32_t w, uint32_t h, uint32_t usage, const char* name,
                                  uint32_t mips = 1) {
    rhi::TextureDesc d;
    d.format = f;
    d.width = w;
    d.height = h;
    d.mipLevels = mips;
    d.usage = usage;
    d.debugName = name;
    return d;
}

inline uint32_t groupsFor(uint32_t n, uint32_t size) { return (n + size - 1) / size; }

}  // namespace bricklight::conformance
