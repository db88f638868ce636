// Bricklight tile classifiers (FidelityFX Classifier-class): the shadow classifier sorts the screen's 8×4 pixel tiles
// by what the sun's shadow maps can decide — pixels surely lit, surely shadowed, and those that need a ray — and
// lists the tiles with rays to trace (through the distance field, bricklight/trace.glsl) with each tile's pixel
// mask and ray interval. docs/shadows.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "bricklight/errors.h"
#include "bricklight/memory_use.h"
#include "bricklight/gbuffer/inputs.h"
#include "bricklight/rhi.h"
#include "bricklight/sdf.h"

namespace bricklight::shadows {

constexpr uint32_t kShadowTileWidth = 8, kShadowTileHeight = 4;  // 32 pixels: bit y·8 + x of a tile's masks
constexpr uint32_t kMaxShadowCascades = 4;
constexpr size_t kShadowParamsBytes = 528;  // the classifier's parameter block (internal)

// Normals: every pixel facing the sun needs a ray over [rayPushOff, ∞) (no shadow maps). Cascades: a blocker
// search in the shadow maps decides what it can and bounds the rays of the rest.
enum class ShadowClassifyMode : uint32_t { Normals, Cascades };

// One cascade of the application's shadow maps.
struct ShadowCascade {
    // World → the shadow texture: x, y its texture coordinates in [0, 1] over the whole texture (an atlas's tile
    // is a part of it), z the depth the map stores in [0, 1], 0 nearest the sun (an orthographic projection).
    glm::mat4 worldToShadow{1.0f};
    glm::vec4 uvRect{0.0f, 0.0f, 1.0f, 1.0f};  // the cascade's part of the texture: min u, min v, max u, max v
    float depthRange = 1.0f;                   // world units from depth 0 to depth 1
};

// Per tile, tileList() holds a uvec4: x = tile x | tile y << 16, y = the mask of pixels that need a ray, z and w the
// ray interval's start and end (floats, world units along the ray towards the sun, from the surface).
struct ShadowClassifyDesc {
    ShadowClassifyMode mode = ShadowClassifyMode::Cascades;
    gbuffer::Camera camera;                    // bricklight/gbuffer/inputs.h
    bricklight::gbuffer::Inputs gbuffer;       // depth, normals, roughness, motion
    glm::vec3 sunDirection{0.0f, 1.0f, 0.0f};  // towards the sun
    float sunAngle = 0.0093f;  // the sun's full angular diameter (radians): widens the blocker search with depth
    // Soft shadows: trace() jitters each ray's direction uniformly over the sun's disc (sunAngle) with a per-pixel,
    // per-frame sample (an R2 sequence over frameIndex, rotated per pixel by a hash: deterministic, the same on
    // every backend), so the hit mask holds one stochastic sample of the penumbra for a denoiser to average
    // (shadows::ShadowDenoiser). Off: rays towards the sun's centre (a hard shadow).
    bool softShadows = false;
    uint32_t frameIndex = 0;  // the sample of this frame (soft shadows); only its low 24 bits count
    // Cascades mode: the shadow texture (D32_FLOAT or R32_FLOAT, sampled; read texel by texel) and its cascades,
    // finest first (each pixel takes the first whose uvRect holds it).
    rhi::TextureHandle shadowMap;
    uint32_t cascadeCount = 0;
    ShadowCascade cascades[kMaxShadowCascades];
    float blockerOffset = 0.002f;  // shadow-map depth a tap must be nearer the sun than the receiver to block it
    uint32_t blockerTaps = 16;     // Poisson taps of the blocker search: 8, 16, 24 or 32
    bool rejectLitPixels = true;   // false: pixels whose taps all lie behind them get a ray too
    bool cascadeRayInterval = true;  // false: rays over [rayPushOff, ∞)
    float rayPushOff = 0.04f;        // world units: the least ray start
    float rayNormalOffset = 0.01f;   // world units the rays' origins move along the normal (trace())
    // Sure rays only (trace()): a ray replaces the maps' answer only where the field's answer is sure, judged by the
    // distance at which the field sees a blocker, not by one hit epsilon. A ray that hits with the field's hit epsilon
    // scaled by sureHitEpsilon (< 1: only where the ray passes through a surface, never beside one) is shadowed; a
    // ray that misses with it scaled by sureMissEpsilon (> 1: a blocker fattened past the field's interpolation
    // error, which can only thin one) is lit, provided the tile's interval starts beyond the ray's own start (no
    // blocker the taps saw nearer than the field can tell from the receiver); every other ray keeps the maps'
    // answer in the hit mask. Each ray starts along its own direction where the field no longer sees its receiver:
    // (its epsilon + selfClearance brixels of the cascade that holds it) / the cosine to the normal (at least 0.1).
    // Off: one ray with the field's epsilon over the tile's interval decides every listed pixel. sureMask() says which
    // pixels' answers are sure (decided by the search or by a sure ray); with markUnsurePixels, resolve() writes −1
    // for the others, so that the application can put its own filtered shadow-map answer there (the hit mask's
    // majority of the taps is a coarser one).
    bool sureRaysOnly = false;
    bool markUnsurePixels = false;
    float sureHitEpsilon = 0.25f, sureMissEpsilon = 2.0f;  // in units of the field's hit epsilon (0.6 brixel); ≤ 3
    float selfClearance = 0.5f;                          // brixels
    // Tiles with this many ray pixels or fewer are not listed: their pixels keep the shadow maps' answer in the
    // hit mask, and readCounts() counts them (0: every tile with a ray is listed).
    uint32_t tileCutOff = 0;
    // Foliage: the GI's alpha (coverage) cache, gi::GiContext::alphaCacheBuffer() of a context created with
    // gi::ContextFlags::AlphaCache whose alpha pass has run (docs/gi.md, "Foliage"). trace()'s rays then go on past
    // the hits the field flags as alpha-tested (sdf::InstanceDesc::alphaTested) with the probability that the card is
    // cut out there, a new draw per pixel and frameIndex, so that the hit mask averaged over frames (the shadow
    // denoiser's history) holds the partial visibility through the cards; with a fixed frameIndex each pixel's draw
    // stays the same (a stable dither). Null: alpha-tested cards are solid to the rays. Must stay live until trace().
    rhi::BufferHandle alphaCache;
};

struct ShadowClassifyCounts {
    uint32_t listedTiles = 0;    // in tileList()
    uint32_t cutOffTiles = 0;    // with ray pixels, not listed (tileCutOff)
    uint32_t rayPixels = 0;      // pixels that need a ray, in listed tiles
    uint32_t cutOffPixels = 0;   // pixels that needed a ray in cut-off tiles
    uint32_t activePixels = 0;   // on-screen, not sky, facing the sun
};

struct ShadowClassifierDesc {
    uint32_t width = 0, height = 0;  // the G-buffer's size in pixels, 1..16384 a side
};

//   resource                 format                              holds
//   shadow tile list         buffer, uvec4 per tile (≤ tiles)    the listed tiles (ShadowClassifyDesc's comment)
//   shadow tile count A, B   buffer, 8 words, indirect args      groups of 8 listed tiles, 1, 1 (dispatchIndirect
//                                                                arguments: 256 threads, 32 per tile), then cut-off
//                                                                tiles, ray pixels, cut-off pixels, active pixels,
//                                                                listed tiles; classify() adds to one and zeroes
//                                                                the other, which the next classify() adds to
//   shadow hit mask          R32_UINT, ⌈W/8⌉ × ⌈H/4⌉            per tile, bit 1: shadowed or not known; 0: lit.
//                                                                Preloaded with the shadow maps' answer (their
//                                                                filtered taps); trace() replaces the listed
//                                                                tiles' masked bits with the rays' answers.
class ShadowClassifier {
public:
    // Null with *error for a zero or too large size, or a device that cannot create the resources.
    static std::unique_ptr<ShadowClassifier> create(rhi::IDevice& device, const ShadowClassifierDesc& desc, Error* error = nullptr);
    ~ShadowClassifier();
    ShadowClassifier(const ShadowClassifier&) = delete;
    ShadowClassifier& operator=(const ShadowClassifier&) = delete;

    // Records the classification; false with *error, recording nothing, for missing or
    // mis-sized inputs or bad parameters.
    bool classify(const ShadowClassifyDesc& desc, Error* error = nullptr);
    // Hybrid shadows, after classify(): one ray per masked pixel of each listed tile (dispatchIndirect on tileCount(),
    // 32 threads a tile, 8 tiles a group) towards the sun's centre (softShadows: a point of its disc) through `field`
    // (an updated distance field of the same scene), over the tile's interval, passing cut-out parts of alpha-tested
    // cards where the classify() gave an alpha cache; hitMask() takes the rays' answers for those pixels. The last
    // classify()'s depth, normals and alpha cache must still be live. False with *error, recording nothing, before
    // any classify() or when they are not.
    bool trace(const sdf::SdfScene& field, Error* error = nullptr);
    // hitMask() per pixel into `output` (R16_FLOAT with Storage usage, the classifier's size): 1 lit, 0 shadowed or
    // facing away from the sun; −1 where the answer is not sure (sureMask()) if the last classify() asked
    // markUnsurePixels.
    bool resolve(rhi::TextureHandle output, Error* error = nullptr);

    rhi::BufferHandle tileList() const { return tiles_; }
    // dispatchIndirect arguments at offset 0, and the counts: the buffer the last classify() wrote (two alternate: read
    // it after each classify(), do not keep it).
    rhi::BufferHandle tileCount() const { return counts_[countIndex_]; }
    rhi::TextureHandle hitMask() const { return hitMask_; }
    // R32_UINT like hitMask(): bit set where the pixel's answer is sure — decided by the blocker search (every tap
    // or none blocking, facing away, sky) or by a sure ray (ShadowClassifyDesc::sureRaysOnly); clear where it is the
    // majority of mixed taps (or beyond every cascade).
    rhi::TextureHandle sureMask() const { return sureMask_; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    uint32_t tilesX() const { return (width_ + kShadowTileWidth - 1) / kShadowTileWidth; }
    uint32_t tilesY() const { return (height_ + kShadowTileHeight - 1) / kShadowTileHeight; }
    ShadowClassifyCounts readCounts();  // waits for the GPU (tests and tools)

    MemoryUse memoryUse() const;  // its textures and buffers on the device

private:
    explicit ShadowClassifier(rhi::IDevice& device) : device_(device) {}
    rhi::IDevice& device_;
    uint32_t width_ = 0, height_ = 0;
    rhi::ShaderHandle classify_, trace_, resolve_;
    rhi::TextureHandle depth_, normals_;  // the last classify()'s (trace())
    rhi::BufferHandle alphaCache_;        // the last classify()'s, or null (trace() binds alphaCacheNone_)
    // trace_shadows.comp always declares the alpha cache (a binding it did not declare would be refused, and one it
    // declares must be bound): without the application's, this 16-byte buffer whose header says "no cache".
    rhi::BufferHandle alphaCacheNone_;
    bool classified_ = false;
    std::array<uint8_t, kShadowParamsBytes> lastParams_{};  // what params_ holds
    bool paramsWritten_ = false;
    rhi::BufferHandle tiles_, params_;
    rhi::BufferHandle counts_[2];  // classify() adds to one and zeroes the other for the next classify()
    uint32_t countIndex_ = 1;      // counts_[countIndex_]: the last classify()'s
    rhi::TextureHandle hitMask_, sureMask_;
    rhi::SamplerHandle point_;
};

}  // namespace bricklight::shadows
