// Bricklight's reflection denoiser for hybrid reflections: a temporal accumulation and an edge-aware spatial filter
// that run only on the tiles the reflection classifier listed for denoising (dispatchIndirect, one 8×8 group per
// tile), so that its cost follows the reflective pixels, not the screen. docs/reflections.md, "Hybrid reflections".
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "bricklight/errors.h"
#include "bricklight/memory_use.h"
#include "bricklight/gbuffer/inputs.h"
#include "bricklight/rhi.h"

namespace bricklight::reflections {

constexpr uint32_t kReflectionDenoiseTile = 8;  // pixels per side of a listed tile (one group of 8×8 threads)

//   input / output        format                         holds
//   tiles                 buffer, uint per tile          a listed tile's top-left pixel: x | y << 16
//   arguments             dispatchIndirect arguments     groups = listed tiles, 1, 1 (at argumentsOffset)
//   count                 uint at countOffset            the number of listed tiles
//   radiance              RGBA16_FLOAT, sampled          this frame's traced reflections: rgb, a = 1 where resolved
//   depth, normals,       the G-buffer, sampled          as the classifier's (normal unpack, roughness channel)
//   roughness
//   output                RGBA16_FLOAT, Storage          rgb the denoised reflection, a its weight in the composite
//                                                        (1: replaces the GI's specular; 0: nothing here — every
//                                                        pixel outside the listed tiles, and pixels with no sample)
//   history (internal)    2 × RGBA16_FLOAT + 2 × R32F    accumulated radiance (a = samples) and its device depth
struct ReflectionDenoiseDesc {
    rhi::BufferHandle tiles;
    rhi::BufferHandle arguments;
    uint64_t argumentsOffset = 0;
    rhi::BufferHandle count;
    uint64_t countOffset = 0;
    rhi::TextureHandle radiance;
    gbuffer::Camera camera;                    // bricklight/gbuffer/inputs.h
    bricklight::gbuffer::Inputs gbuffer;       // depth, normals, roughness, motion
    // Most frames a pixel accumulates: mirrors keep fewer (their reflections move against the surface when the camera
    // moves, and surface-motion reprojection cannot follow that), rough surfaces up to this many.
    uint32_t maxHistory = 16;
    bool resetHistory = false;  // a camera cut: forget the history
    rhi::TextureHandle output;
};

struct ReflectionDenoiserDesc {
    uint32_t width = 0, height = 0;  // the G-buffer's size in pixels, 1..16384 a side
};

class ReflectionDenoiser {
public:
    // Null with *error for a zero or too large size, or a device that cannot create the resources.
    static std::unique_ptr<ReflectionDenoiser> create(rhi::IDevice& device, const ReflectionDenoiserDesc& desc, Error* error = nullptr);
    ~ReflectionDenoiser();
    ReflectionDenoiser(const ReflectionDenoiser&) = delete;
    ReflectionDenoiser& operator=(const ReflectionDenoiser&) = delete;

    // Records this frame's clears, the temporal pass and the spatial pass. False with *error, recording nothing, for
    // missing, dead or mis-sized resources or bad parameters.
    bool denoise(const ReflectionDenoiseDesc& desc, Error* error = nullptr);

    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }

    MemoryUse memoryUse() const;  // its textures and buffers on the device

private:
    explicit ReflectionDenoiser(rhi::IDevice& device) : device_(device) {}
    rhi::IDevice& device_;
    uint32_t width_ = 0, height_ = 0;
    uint32_t frame_ = 0;  // which history is written this frame (frame_ & 1)
    bool historyValid_ = false;
    rhi::ShaderHandle temporal_, spatial_, clear_;
    rhi::TextureHandle history_[2], historyDepth_[2];
    rhi::BufferHandle params_;
    rhi::SamplerHandle point_, linear_;
};

}  // namespace bricklight::reflections
