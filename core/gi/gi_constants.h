// C++ mirror of the GI passes' constant blocks (shaders/gi/gi_common.glsl): std140, vec4-aligned.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace bricklight::gi::detail {

struct GpuCamera {  // BL_CONSTANTS(0)
    glm::mat4 viewProjection;
    glm::mat4 inverseViewProjection;
    glm::mat4 previousViewProjection;
    glm::mat4 previousInverseViewProjection;
};
static_assert(sizeof(GpuCamera) == 256);

enum GpuFlags : uint32_t {
    FlagReversedDepth = 1u,
    FlagResetHistory = 2u,
    FlagHistoryValid = 8u,
    FlagCameraMotion = 16u,  // no motion vectors: downsample.comp derives them from depth and the cameras
    FlagProbeParallax = 32u,  // reproject_probes.comp marks carried texels whose hit lies elsewhere from the new probe
};

struct GpuFrame {  // BL_CONSTANTS(1)
    uint32_t size[4];       // internal w, h, display w, h
    uint32_t tiles[4];      // probe tiles x, y, frame index, flags
    glm::vec4 camera;       // position, finest traced voxel size
    glm::vec4 normalScale;  // xyz, w roughness threshold
    glm::vec4 normalOffset; // xyz, w environment intensity
    uint32_t inputs[4];     // roughness channel, roughness perceptual, environment kind, max history
    glm::vec4 motion;       // xy scale
    glm::vec4 trace;        // push-off, specular push-off, tMin, tMax
    uint32_t cascades[4];   // start, end, atlas bricks per axis, brick capacity
    glm::vec4 epsilon;      // diffuse, specular epsilon scale
    uint32_t relight[4];    // light count, relight flags (RelightFlags), unused, unused
    glm::vec4 traceLimits;  // iterations per cascade of every GI ray, diffuse rays' coarsenAfterVoxels (TraceParams)
    uint32_t probes[4];     // probe tile side in internal pixels, unused, unused, unused
    uint32_t cache[4];      // radiance cache slots kept for injections that carry light, changed regions, unused, unused
};
static_assert(sizeof(GpuFrame) == 224);

// Where the field's geometry changed (SdfScene::latestChanges: a mover's old and new bounds), GI refreshes its
// light. Last frame's image, which the cache learns from, and the pixels' history hold the light of before the
// change: for kChangeFeedbackFrames frames the radiance cache of the bricks there is dropped and nothing is
// injected there (probes light those hits as surfaces never seen), and for kChangeFrames frames the pixels there
// keep a history of at most kChangeHistory samples. A change reaches as far as the changed box's largest side
// (an object's colour bleeding and shadow are strongest within about its size), at least kChangeReachVoxels
// finest traced voxels. At most kMaxChangedRegions boxes: more are merged (the least added volume first).
constexpr uint32_t kMaxChangedRegions = 8;
constexpr float kChangeReachVoxels = 2.0f;
constexpr uint32_t kChangeHistory = 2;
constexpr uint64_t kChangeFrames = 8;
constexpr uint32_t kChangeFeedbackFrames = 2;

struct GpuChangedRegions {  // BL_CONSTANTS(3) of clear_freed_bricks.comp and interpolate.comp
    glm::vec4 boxes[2 * kMaxChangedRegions];  // world min, max (grown by the reach); GpuFrame::cache[1] of them
};
static_assert(sizeof(GpuChangedRegions) == 256);

enum RelightFlags : uint32_t {
    RelightAlbedo = 1u,    // DispatchDesc::diffuseAlbedo given: bricks learn their albedo, unseen texels are re-lit
    RelightEmission = 2u,  // DispatchDesc::emission given
    RelightEmissionInRays = 4u,  // the lit image leaves emission out: relight rays add it at their hits
    RelightEmittersInLights = 8u,  // DispatchDesc::emittersInLights: relight rays take no emission at their hits
    RelightLitHoldsEmission = 16u,  // DispatchDesc::previousLitIncludesEmission: probe rays' unseen hits add the field's
    RelightDirectOnly = 32u,  // !DispatchDesc::relightBounces: surfaces GI lights itself take the lights and emission only
    RelightUnseenHits = 64u,  // DispatchDesc::lightUnseenSurfaces: probe rays light the surfaces no view has lit
    RelightEnvironmentInDirect = 128u,  // DispatchDesc::environmentInDirectLight: only surfaces GI lights itself take the environment
};

// One light in the lights buffer (std430, 4 × vec4; shaders/gi/gi_lights.glsl reads it).
struct GpuLight {
    glm::vec4 position;   // xyz (an area light's corner), w type (gi::LightType)
    glm::vec4 direction;  // xyz unit (towards a directional light; a spot's axis) or an area light's edge0;
                          // w cos(spot inner angle), or 1 for a two-sided area light
    glm::vec4 color;      // rgb, w cos(spot outer angle)
    glm::vec4 edge1;      // xyz an area light's edge1, w its area
};
static_assert(sizeof(GpuLight) == 64);

constexpr uint32_t kProbeTexels = 8;  // octahedral texels per probe side (8×8 rays)
// Internal pixels per probe tile side when ContextDesc::probeTile is 0: 8, 16 from an internal width of
// 1440 on (spawn_probes.comp says why).
constexpr uint32_t probeTileFor(uint32_t internalWidth) { return internalWidth >= 1440 ? 16 : 8; }
// One injected pixel per tile per frame (GI_INJECT_TILE) when ContextDesc::injectTile is 0: 2×2 tiles,
// 4×4 from an internal width of 1440 on (inject_radiance.comp says why).
constexpr uint32_t injectTileFor(uint32_t internalWidth) { return internalWidth >= 1440 ? 4 : 2; }
constexpr uint32_t kPretraceTile = 4;       // one specular pre-trace ray per 4×4 tile
constexpr uint32_t kCacheTexelsPerBrick = 4;  // radiance cache texels per brick side
constexpr uint32_t kCacheSlotsPerLayer = 64 * 64;  // slots per 4-texel layer of the cache image (giCacheSlotBase)
constexpr uint32_t kDefaultCacheSlots = 65536;     // ContextDesc::radianceCacheBricks = 0
constexpr uint32_t kShCoefficients = 9;
constexpr uint32_t kMaxDiffuseHistory = 16;
constexpr uint32_t kBrickMaterialWords = 3;  // per brick: albedo (RGBA8), emission (RGB9E5), frame last seen + 1
constexpr uint32_t kRelightBudget = 2048;    // bricks re-lit per frame at most (GI_RELIGHT_BUDGET)
// An empty relight list's header: indirect dispatch arguments (0, 1, 1), no candidates (clear_freed_bricks.comp
// writes the same into the next frame's list).
constexpr uint32_t kEmptyRelightList[4] = {0, 1, 1, 0};

// The alpha cache (shaders/gi/gi_alpha.glsl, include/bricklight/alpha_pass.glsl): a header, then one
// word per 4³ cell of every brick; the alpha pass rasterizes each cascade's 64 voxels at 2 pixels per cell.
constexpr uint32_t kAlphaCacheHeaderWords = 4;
constexpr uint32_t kAlphaCellsPerBrick = 64;
constexpr uint32_t kAlphaPassResolution = 64 * 4 * 2;

}  // namespace bricklight::gi::detail
