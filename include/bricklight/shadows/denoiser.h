// The shadow denoiser: turns hybrid soft shadows' one stochastic ray per pixel (shadows::ShadowClassifier with
// softShadows, a new frameIndex each frame) into a smooth visibility, working on the classifier's tile list only —
// temporal accumulation (reprojected with depth and last frame's camera, rejected where depth or normal show a
// disocclusion, clamped to the current neighbourhood's mean ± clampSigma·σ so that moving shadows do not ghost) then
// an edge-aware à-trous filter (depth-plane, normal and visibility weights), both dispatched indirectly on the
// classifier's count buffer. Pixels that needed no ray (unlisted tiles, and the unmasked pixels of listed ones) take
// the hit mask's decided answer exactly, and their history is kept consistent with it. docs/shadows.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "bricklight/shadows/classifier.h"
#include "bricklight/errors.h"
#include "bricklight/memory_use.h"
#include "bricklight/gbuffer/inputs.h"
#include "bricklight/rhi.h"

namespace bricklight::shadows {

constexpr uint32_t kMaxShadowDenoiseHistory = 64;
constexpr uint32_t kMaxShadowFilterPasses = 5;

struct ShadowDenoiseDesc {
    gbuffer::Camera camera;                    // bricklight/gbuffer/inputs.h
    bricklight::gbuffer::Inputs gbuffer;       // depth, normals, roughness, motion
    rhi::TextureHandle output;  // R16_FLOAT with Storage usage, the denoiser's size: 1 lit, 0 shadowed
    // Start over (the first frame, a cut): the history is not read. The first denoise() after create() must set it.
    bool resetHistory = false;
    uint32_t maxHistory = 32;    // frames the temporal average spans at most (1..kMaxShadowDenoiseHistory)
    float clampSigma = 1.0f;     // the history is clamped to the current 7×7 neighbourhood's mean ± clampSigma·σ (> 0)
    float depthTolerance = 0.02f;  // a reprojected or filtered neighbour's distance from the pixel's plane, as a
                                   // fraction of the pixel's distance from the camera, that still counts as the same surface
    uint32_t filterPasses = 3;   // à-trous passes of 3×3 taps, steps 1, 2, 4, ... (0..kMaxShadowFilterPasses)
};

struct ShadowDenoiserDesc {
    uint32_t width = 0, height = 0;  // the G-buffer's size in pixels, 1..16384 a side
};

//   resource                    format                          holds
//   shadow denoiser history ×2  RGBA16_FLOAT, W × H              ping-pong: mean visibility, its second moment,
//                                                                frames accumulated (a pixel that needed no ray:
//                                                                its answer, answer², 1)
//   shadow denoiser geometry ×2 RG32_UINT, W × H                 ping-pong: the depth's bits, the normal
//                                                                (octahedral, 2 × 16-bit unorm) — last frame's for
//                                                                the disocclusion test
//   shadow denoiser filter ×2   R16_FLOAT, W × H                 the à-trous passes' ping-pong (listed tiles only)
//   shadow denoiser tiles       R32_UINT, ⌈W/8⌉ × ⌈H/4⌉          1 for the tiles listed this frame (cleared per frame)
//   shadow denoiser parameters  buffer, 272 bytes                cameras and options (written when they change)
//
//   pass                         dispatch                               reads → writes
//   temporal (denoise_shadows_temporal.comp)  indirect on tileCount(), 8 tiles a group   hit mask, depth, normals,
//                                history[prev], geometry[prev] → history[cur], geometry[cur], tiles
//   decided (denoise_shadows_decided.comp)    16 × 16 groups over the screen     tiles, hit mask, depth, normals →
//                                history[cur], geometry[cur], output (unlisted tiles' pixels only)
//   filter × passes (denoise_shadows_filter.comp)  indirect on tileCount()  history[cur] or filter, geometry[cur],
//                                hit mask, tiles → filter, the last pass output (listed tiles' pixels only)
class ShadowDenoiser {
public:
    // Null with *error for a zero or too large size, or a device that cannot create the resources.
    static std::unique_ptr<ShadowDenoiser> create(rhi::IDevice& device, const ShadowDenoiserDesc& desc, Error* error = nullptr);
    ~ShadowDenoiser();
    ShadowDenoiser(const ShadowDenoiser&) = delete;
    ShadowDenoiser& operator=(const ShadowDenoiser&) = delete;

    // After classifier.trace() (classify() alone works too: the hit mask's answers are then the maps'): records the
    // passes above into desc.output. False with *error naming the object, recording nothing, for a classifier of
    // another size, mis-sized or wrongly formatted textures, bad parameters, or no history (resetHistory unset on
    // the first call).
    bool denoise(const ShadowClassifier& classifier, const ShadowDenoiseDesc& desc, Error* error = nullptr);

    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    // The accumulated history of the latest denoise() (RGBA16_FLOAT; tests and debug views).
    rhi::TextureHandle history() const { return history_[current_]; }

    MemoryUse memoryUse() const;  // its textures and buffers on the device

private:
    explicit ShadowDenoiser(rhi::IDevice& device) : device_(device) {}
    rhi::IDevice& device_;
    uint32_t width_ = 0, height_ = 0;
    rhi::ShaderHandle temporal_, decided_, filter_;
    rhi::TextureHandle history_[2], geometry_[2], filtered_[2], listed_;
    rhi::BufferHandle params_;
    rhi::SamplerHandle point_;
    uint32_t current_ = 0;
    bool hasHistory_ = false;
    std::array<uint8_t, 272> lastParams_{};
    bool paramsWritten_ = false;
};

}  // namespace bricklight::shadows
