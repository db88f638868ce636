// Small helpers shared by the conformance cases: CPU decoding of formats, byte views, record shortcuts, and
// the case lists (case_lists.h).
#pragma once

#include <cstring>
#include <vector>

#include "bricklight/conformance.h"
#include "bricklight/half.h"
#include "case_lists.h"

namespace bricklight::conformance {

using bricklight::halfToFloat;
uint16_t floatToHalf(float f);
// Decodes an R11G11B10_FLOAT texel to three floats.
void decodeR11G11B10(uint32_t packed, float out[3]);
// Decodes an RGB9E5_FLOAT texel (shared exponent) to three floats.
void decodeRgb9e5(uint32_t packed, float out[3]);
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

// Dispatches rhi_tests/chain_step.comp over whole buffers, one thread per element: dst[i] = src[i] * 2 + step
// for i < count. (A helper that dispatches rather than returns the state: constants are read at the call.)
inline bool dispatchChainStep(rhi::IDevice& device, rhi::ShaderHandle shader, const char* label, rhi::BufferHandle src,
                              rhi::BufferHandle dst, uint32_t count, uint32_t step) {
    struct { uint32_t count, step; } p{count, step};
    rhi::DispatchState s;
    s.shader = shader;
    s.label = label;
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.readBuffers.push({0, src, {}});
    s.bindings.storageBuffers.push({0, dst, {}, rhi::Access::Write});
    return device.dispatch(s, groupsFor(count, 64), 1, 1);
}

}  // namespace bricklight::conformance
