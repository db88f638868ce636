// Bricklight hierarchical depth pyramid: from a depth texture (the G-buffer's, or the application's own), a mip
// chain of RG32_FLOAT texels holding the closest (r = min) and the farthest (g = max) depth of their footprint,
// for the classifiers' blocker search and the screen-space reflection trace's hierarchical steps. An engine
// that builds its own pyramid hands that to the consumers instead. docs/gbuffer.md.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "bricklight/errors.h"
#include "bricklight/memory_use.h"
#include "bricklight/rhi.h"

namespace bricklight::gbuffer {

struct DepthPyramidDesc {
    uint32_t width = 0, height = 0;  // the G-buffer's size in pixels, 1..16384 a side
};

// Mip 0 has the depth texture's size and holds each pixel's depth twice; mip n + 1 has the sizes of a texture's
// mip chain (rhi::mipExtent: halved and rounded down, never below 1) and its texel (x, y) covers the texels
// 2x..2x+1, 2y..2y+1 of mip n, plus the last column (row) of mip n where its width (height) is odd and x (y) is
// the last column (row): every texel of mip n lies under exactly one texel of mip n + 1. So pixel p lies under
// texel min(p >> n, mipExtent(size, n) − 1) of mip n. Depth is as the source holds it (the comparison is plain
// min/max: with reversed Z, r is the farthest and g the closest).
class DepthPyramid {
public:
    // A pyramid for depth textures of width × height (1..16384 each): every mip down to 1 × 1. Null with *error
    // when the size is out of range or the device refuses the texture or the passes' shaders.
    static std::unique_ptr<DepthPyramid> create(rhi::IDevice& device, const DepthPyramidDesc& desc, Error* error = nullptr);
    ~DepthPyramid();
    DepthPyramid(const DepthPyramid&) = delete;
    DepthPyramid& operator=(const DepthPyramid&) = delete;
    // Records the passes (one dispatch per five mips) that rebuild the whole pyramid from `depth` (D32_FLOAT or
    // R32_FLOAT, sampled, 2D, of the pyramid's size; mip 0 is read). False with *error, recording nothing, for a
    // dead handle or a texture of another size, format or kind.
    bool build(rhi::TextureHandle depth, Error* error = nullptr);
    rhi::TextureHandle texture() const { return texture_; }  // RG32_FLOAT, Sampled | Storage, mipCount() mips
    uint32_t mipCount() const { return mipCount_; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }

    MemoryUse memoryUse() const;  // its textures and buffers on the device

private:
    explicit DepthPyramid(rhi::IDevice& device) : device_(device) {}
    rhi::IDevice& device_;
    rhi::TextureHandle texture_;
    rhi::TextureHandle unusedMips_;  // bound to the mip slots a dispatch leaves unused (never written)
    rhi::ShaderHandle first_, next_;
    rhi::SamplerHandle point_;
    uint32_t width_ = 0, height_ = 0, mipCount_ = 0;
};

// The mip count of a full pyramid over width × height: floor(log2(max(width, height))) + 1.
uint32_t depthPyramidMipCount(uint32_t width, uint32_t height);

}  // namespace bricklight::gbuffer
