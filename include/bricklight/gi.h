// Bricklight dynamic diffuse and specular GI from a G-buffer, traced against an sdf::SdfScene (the
// Brixelizer GI technique, with our own fixes): a per-brick radiance cache fed from the previous lit frame,
// screen probes on 8×8 tiles traced through the distance field, a per-brick world-space SH irradiance
// cache, a specular trace, temporal accumulation and a bilateral denoiser. Every pass is a record for
// rhi::IDevice. See docs/gi.md for the passes, resources and conventions.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bricklight/reflections/ray_list.h"
#include "bricklight/errors.h"
#include "bricklight/memory_use.h"
#include "bricklight/gbuffer/inputs.h"
#include "bricklight/rhi.h"
#include "bricklight/sdf.h"

namespace bricklight::vct {
class Clipmap;
}

namespace bricklight::gi {

// The scale at which GI is computed; the outputs are upsampled to the display size.
enum class InternalResolution : uint8_t { Native, Percent75, Percent50, Percent25 };
float internalScale(InternalResolution resolution);

namespace ContextFlags {
enum : uint32_t {
    NoSpecular = 1u << 0,    // no specular rays: the specular output is the irradiance cache's lobe estimate
    NoDenoiser = 1u << 1,    // skip the bilateral blur
    ReversedDepth = 1u << 2, // the depth buffer has 1 at the near plane and 0 at the far plane (sky)
    // No camera self-check (docs/gi.md, "Integration contract"): for a G-buffer that holds much geometry the
    // scene does not, or an orthographic projection (the check would warn that positions rebuilt from depth
    // lie off the field's surfaces or that the camera is not at cameraPosition).
    NoCameraCheck = 1u << 3,
    // Keep an alpha (coverage) cache beside the radiance cache (docs/gi.md, "Foliage"): 4³ cells per brick
    // (256 B per brick of the scene's capacity), filled by the application's alpha pass (alphaPassState), with
    // which the GI's rays go on past the cut-out parts of instances registered as alpha-tested
    // (sdf::InstanceDesc::alphaTested). Without it those instances' cards are solid to the GI. Needs geometry
    // shaders.
    AlphaCache = 1u << 4,
    // Carry the screen probes' texels from one frame to the next without the parallax test (docs/gi.md,
    // *Departures*, "Probe rays"): no texel is traced again because the light it carries lies in another direction
    // from the new probe. Cheaper, most with a moving camera (docs/performance.md has the figures), but the light
    // comes from the wrong places where a wall is seen at grazing angles or objects stand near the probes: the
    // `corridor`'s indirect light drifts to two thirds of the path tracer's.
    NoProbeParallax = 1u << 5,
};
}

struct ContextDesc {
    uint32_t displayWidth = 0;
    uint32_t displayHeight = 0;
    InternalResolution internalResolution = InternalResolution::Percent50;
    uint32_t flags = 0;
    // Bricks that can hold radiance at once (4³ texels, 256 B each): a brick gets a slot when light is
    // first injected into it and gives it back when the SDF frees it; when all are taken, further bricks
    // stay uncached until some are freed. 0: min(the scene's brick capacity, 65536) = 16 MiB.
    uint32_t radianceCacheBricks = 0;
    // The injection of the lit image into the radiance cache takes one pixel of each injectTile ×
    // injectTile tile a frame (1, 2, 4 or 8). 0: 2, or 4 from an internal width of 1440 on — the cache's
    // texels are a fixed size in the world, so at higher resolutions more pixels reach each of them.
    uint32_t injectTile = 0;
    // One screen probe per probeTile × probeTile internal pixels (8 or 16). 0: 8, or 16 from an internal
    // width of 1440 on — the probes then keep about the same density on the screen as 8 at 960x540, and
    // at 1920x1080 internal a quarter of the probes' tracing and projection (docs/gi.md, "Probe tiles").
    uint32_t probeTile = 0;
    std::string debugName = "gi";
    // Receives the context's own messages (bad inputs); stderr when empty.
    rhi::ErrorCallback errorCallback;
};

enum class EnvironmentKind : uint8_t { None, Cube, Equirectangular };

// Tracing parameters. Distances are world units.
struct TraceParams {
    uint32_t startCascade = 0;
    uint32_t endCascade = sdf::kMaxCascades - 1;  // clamped to the scene's cascades
    // Ray origins move this far along the normal; 0: half a voxel of the finest traced cascade that holds
    // the point (clears the hit epsilon and the distance band).
    float rayPushOff = 0.0f;
    float specularRayPushOff = 0.0f;
    float epsilonScale = 1.0f;        // multiplies the SDF's hit epsilon for diffuse rays
    float specularEpsilonScale = 1.0f;
    float tMin = 0.0f;
    float tMax = 1e30f;
    // Node, voxel and sphere-tracing steps a GI ray may take in one cascade before it goes on in the next
    // coarser one (BlSdfRay::maxIterations; 1..kMaxTraceIterations). The published technique uses 32: the
    // slowest rays (grazing a surface, crossing busy fine cascades) set each tracing pass's time, and a
    // coarser answer for them costs little light. A ray that runs out in the last cascade counts as
    // "unknown" (no vote), not as the sky.
    uint32_t maxIterationsPerCascade = 32;
    // Diffuse rays stand for cones (64 per probe): once one has gone this many voxels of its current
    // cascade, it goes on in the next coarser cascade (BlSdfRay::coarsenAfterVoxels), as the cone's
    // footprint has outgrown the finer voxels. Fewer steps per ray; 0 turns it off (a ray leaves a cascade
    // only at its boundary). Specular rays of GGX roughness α coarsen after max(1, 0.35 / 2.6α) times this
    // (where their lobe, about 2.6α across, has a diffuse ray's footprint), shadow rays never.
    float coarsenAfterVoxels = 4.0f;
};
constexpr uint32_t kMaxTraceIterations = 4096;

// A light of the application's direct lighting, for relighting the radiance cache where the camera does
// not see (DispatchDesc::lights). Units are the lit image's.
// Area lights (Rect, Triangle) are the emitting surfaces an application samples in its direct lighting: the
// parallelogram with corners position, position + edge0, position + edge0 + edge1, position + edge1, or the
// triangle position, position + edge0, position + edge1. They emit `color` as radiance (W/(sr·m²)) from the side
// cross(edge0, edge1) faces (from both with twoSided); relighting samples one point of each per texel and frame.
enum class LightType : uint8_t { Directional, Point, Spot, Rect, Triangle };
struct Light {
    LightType type = LightType::Point;
    glm::vec3 position{0.0f};                // point, spot; rect, triangle: a corner
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // directional: towards the light; spot: the cone's axis (away from the light)
    glm::vec3 color{0.0f};                   // directional: irradiance on a surface facing it; point, spot: intensity (W/sr);
                                             // rect, triangle: radiance
    float spotInnerAngle = 0.0f;             // spot: half-angles (radians) of full light and of no light
    float spotOuterAngle = 0.0f;
    glm::vec3 edge0{0.0f}, edge1{0.0f};      // rect, triangle: the edges from `position`
    bool twoSided = false;                   // rect, triangle: emits from both sides
};
constexpr uint32_t kMaxLights = 64;

// One frame's inputs. Textures are the application's (Sampled usage); the G-buffer inputs are display
// sized. Matrices are GLM column-major; projections map to depth [0, 1] (reversed with
// ContextFlags::ReversedDepth) and NDC y = -1 at the image's top row (the RHI contract's top-left origin):
// glm::perspectiveRH_ZO(...) then projection[1][1] = -projection[1][1]. docs/gi.md, "Input conventions".
//
//   input                        required  channels  size
//   depth                        yes       exactly 1 display   (D32_FLOAT, R32_FLOAT, R16_FLOAT)
//   normals                      yes       >= 3      display
//   roughness                    yes       >= 1      display   (roughnessChannel selects)
//   previousLitOutput            yes       >= 3      any
//   outputDiffuse                yes       RGBA16_FLOAT, display, Storage
//   motionVectors                no        >= 2      display   (none: a still world, motion from the cameras)
//   outputSpecular               no with NoSpecular, else yes
//   diffuseAlbedo                no        >= 3      display   (turns relighting on)
//   emission                     no        >= 3      display   (needs diffuseAlbedo)
//   lights                       no        lightCount <= kMaxLights (needs diffuseAlbedo)
//   environmentMap               with environmentKind != None
struct DispatchDesc {
    gbuffer::Camera camera;                    // bricklight/gbuffer/inputs.h
    bricklight::gbuffer::Inputs gbuffer;       // depth, normals, roughness, motion
    glm::vec3 cameraPosition{0.0f};

    float roughnessThreshold = 0.75f;     // perceptual roughness above which no specular rays are traced
    // The previous frame's lit image (the light that surfaces send into the scene): feeds the radiance
    // cache. Any size; sampled by UV.
    rhi::TextureHandle previousLitOutput;
    EnvironmentKind environmentKind = EnvironmentKind::None;
    rhi::TextureHandle environmentMap;    // cube, or 2D equirectangular (docs/gi.md gives the mapping)
    float environmentIntensity = 1.0f;
    // The environment is part of the application's direct lighting (a sky its direct pass lights pixels with, as
    // light from a direction that reaches them unblocked): the screen's light then already holds it, so rays GI traces
    // for pixels (probe rays, specular and reflection rays) take nothing where they leave the scene — it would count
    // twice — while GI takes it where it lights surfaces itself, in place of the screen: re-lit texels off screen
    // (relighting) and, with lightUnseenSurfaces, the surfaces no view has lit. Without it (false) every ray that
    // leaves the scene takes the environment, and re-lit texels lose a sky the direct lighting gave them once they
    // are out of view (docs/gi.md, "Relighting").
    bool environmentInDirectLight = false;

    // Off-screen relighting (docs/gi.md, "Relighting"): with the surfaces' diffuse albedo (linear RGB,
    // display size) the cache learns each brick's albedo (and, with `emission`, its emitted radiance) where
    // the camera sees it; texels of bricks the camera has not seen for a few frames are then re-lit from
    // `lights` (shadowed through the distance field), the emission and rays into the cache, so that light
    // which changes out of view still reaches the cache. Without diffuseAlbedo the cache learns only from
    // the screen.
    rhi::TextureHandle diffuseAlbedo;
    rhi::TextureHandle emission;          // optional: emitted radiance (linear RGB, display size)
    // Whether previousLitOutput includes the emission. True: re-lit texels emit it themselves. False (a
    // renderer whose direct lighting samples the emitters, so the lit image fed back leaves them out):
    // re-lit texels leave it out too, and their rays add the emission of the bricks they hit.
    bool previousLitIncludesEmission = true;
    const Light* lights = nullptr;        // lightCount entries, at most kMaxLights
    uint32_t lightCount = 0;
    // The lights include every emitting surface of the scene (as Rect and Triangle lights): relight rays then take
    // no emission where they hit an emitter, since the lights' shadow rays bring its light (sampling an emitter
    // towards each texel is far less noisy than waiting for rays to hit it, and an emitter lights only the side it
    // faces). Needs previousLitIncludesEmission = false: a cache that held the emission would count it twice.
    bool emittersInLights = false;
    // `lights` (with the emitters: emittersInLights, or the emission in the lit image) hold all of the application's
    // direct light: probe rays that meet a surface no view has lit (no light cached for it) then light it where they
    // meet it, from the field's material (sdf::InstanceDesc::material), these lights and the probe's light (docs/gi.md,
    // "Surfaces no view has lit"). Leave it false where the direct lighting holds light GI is not given, such as a sky:
    // such surfaces would miss it, and the stand-in (the light of their neighbouring directions) is better then.
    // Needs diffuseAlbedo.
    bool lightUnseenSurfaces = false;
    // Whether the surfaces GI lights itself (re-lit texels off screen, and the surfaces probe rays meet that no view
    // has lit) take light from other surfaces too (true: every bounce, as the screen's feedback gives on screen), or
    // only from the lights and their emission (false: with a lit image that holds direct light only, GI then gives
    // exactly one bounce — for comparing bounce by bounce with a path tracer).
    bool relightBounces = true;

    TraceParams trace;
    // Forget screen-space history (camera cut): temporal accumulation and probe reuse restart; the
    // world-space caches are kept (they remain true).
    bool resetHistory = false;

    rhi::TextureHandle outputDiffuse;     // RGBA16_FLOAT, display size, Storage usage
    rhi::TextureHandle outputSpecular;    // RGBA16_FLOAT, display size, Storage usage (may be null with NoSpecular)

    // Optional: a voxel clip-map of the same scene with emittance (vct.h), voxelized this frame from the app's
    // draws. Probe rays that hit a surface no view has lit yet (no radiance cached) take the light its voxels hold
    // instead of their neighbours' as a stand-in. Bound at texture slots 0..6 and read buffer 1 of the probe pass.
    const vct::Clipmap* unseenLight = nullptr;
};

// Hybrid reflections' distance-field half (docs/reflections.md, "Hybrid reflections"): after this frame's dispatch(),
// one reflection ray per listed display pixel, traced through the whole field (not only inside a pre-traced brick as
// the GI's own specular rays are), reading the radiance cache where it hits and the environment where it leaves the
// field. Each pixel's ray is blReflectionDirection's (include/bricklight/reflection_ray.glsl) for its
// normal, roughness and `frameIndex`, so that a ray the screen-space trace gave up on continues as the same ray.
//   input / output        holds
//   rays                  uint per entry: display pixel x | y << 15, bits 29..31 copy flags (the pixel's horizontal,
//                         vertical and diagonal quad neighbours take its result too); 0xFFFFFFFF: skipped
//   arguments             dispatchIndirect arguments (groups of kReflectionRaysPerGroup entries,
//                         bricklight/reflections/ray_list.h) at argumentsOffset
//   count                 the number of entries, a uint at countOffset (entries past it are skipped)
//   output                RGBA16_FLOAT, display size, Storage: at each traced pixel rgb radiance and a = 1; a = 0
//                         where the ray gave up (out of iterations) or hit a surface no light was cached for yet.
//                         Other texels are left as they are.
// The depth, normals and roughness are the last dispatch()'s (still live).
using bricklight::kReflectionRaysPerGroup;  // the ray list contract (bricklight/reflections/ray_list.h)
struct ReflectionRaysDesc {
    rhi::BufferHandle rays;
    rhi::BufferHandle arguments;
    uint64_t argumentsOffset = 0;
    rhi::BufferHandle count;
    uint64_t countOffset = 0;
    uint32_t frameIndex = 0;
    rhi::TextureHandle output;
};

enum class DebugMode : uint32_t {
    RadianceCache,     // primary rays through the SDF, coloured by the radiance cache at the hit
    IrradianceCache,   // primary rays, the brick SH irradiance for the hit normal
    ProbesOctahedral,  // the screen probes' 8×8 radiance texels (equal-area hemisphere mapping), tiled over the screen
    ProbesSH,          // each pixel's nearest screen probe SH, evaluated for the pixel's normal
    Disocclusion,      // white: history kept, black: rejected
    SampleCount,       // diffuse history length (white = the maximum)
};

struct DebugViewDesc {
    DebugMode mode = DebugMode::RadianceCache;
    rhi::TextureHandle output;  // RGBA8_UNORM with Storage usage, display size (tone-mapped x / (1 + x))
    float exposure = 1.0f;
};

using MemoryUse = bricklight::MemoryUse;  // named resources and their bytes

class GiContext {
public:
    // Null (with a message through the error callback and `error`) on a bad description or a
    // device that lacks a format the passes need. The context follows `scene` (its caches are sized by the
    // scene's brick capacity): destroy the context first. A context whose scene is gone refuses every call
    // with ErrorCode::DependencyDestroyed.
    static std::unique_ptr<GiContext> create(rhi::IDevice& device, const sdf::SdfScene& scene, const ContextDesc& desc,
                                             Error* error = nullptr);
    virtual ~GiContext() = default;

    // Records one frame of GI. False (changing nothing, recording nothing) on missing or mismatched inputs,
    // with a message that names the input and the problem.
    virtual bool dispatch(const DispatchDesc& desc) = 0;
    // Traces a list of reflection rays (ReflectionRaysDesc) after this frame's dispatch(). False (recording
    // nothing) before any dispatch or on missing or mismatched resources, with a message naming them.
    virtual bool traceReflectionRays(const ReflectionRaysDesc& desc) = 0;
    // Draws a debug view of the latest dispatch into desc.output.
    virtual bool debugView(const DebugViewDesc& desc) = 0;
    // Drops everything: the world-space caches and the screen history.
    virtual void reset() = 0;

    virtual MemoryUse memoryUse() const = 0;
    virtual const ContextDesc& desc() const = 0;
    virtual uint32_t internalWidth() const = 0;
    virtual uint32_t internalHeight() const = 0;
    // Internal pixels per probe tile side (ContextDesc::probeTile, resolved).
    virtual uint32_t probeTile() const = 0;
    virtual const Error& lastError() const = 0;  // the latest error (code None if none)
    // Every distinct message so far (errors, and the warnings of the camera self-check), with how often it
    // was reported: a message repeated every frame reaches the callback once.
    virtual std::vector<Diagnostic> diagnostics() const = 0;

    // For tests and tools (blocking read-backs): the world caches as floats. `radiance` gets 3 floats per
    // cache texel (64 per slot, in the cache image's layout); `brickSH` gets 27 floats (9 RGB coefficients)
    // plus the sample weight per brick (28 floats per brick).
    virtual void readCaches(std::vector<float>* radiance, std::vector<float>* brickSH) = 0;
    // Radiance cache slots in use (a blocking read-back; for tools and tuning radianceCacheBricks).
    virtual uint32_t radianceCacheBricksInUse() = 0;

    // The alpha pass (ContextFlags::AlphaCache; docs/gi.md, "Foliage"): each frame before dispatch() (or when
    // alpha-tested geometry moved or the field's bricks changed), the application draws its alpha-tested
    // instances with this state, its own vertex shader (bricklight/alpha_pass_vertex.glsl: the world position
    // and one vector of its own) and fragment shader (bricklight/alpha_pass.glsl: its alpha test), and the
    // resources those read. Every draw with states taken between two dispatch() calls belongs to one pass.
    // Nullopt (and `error`) without ContextFlags::AlphaCache or geometry shaders, or once the scene is gone.
    virtual std::optional<rhi::DrawCallState> alphaPassState(rhi::ShaderHandle fragmentShader, Error* error = nullptr) = 0;
    // For tests and tools (blocking read-back): per brick of the scene's capacity, 64 cells in the field's cell
    // order ((z·4 + y)·4 + x) of the coverage the alpha passes found there, -1 where none reached; with
    // `fragments`, how many fragments the latest pass counted in each cell. Empty without ContextFlags::AlphaCache.
    virtual std::vector<float> readAlphaCoverage(std::vector<uint32_t>* fragments = nullptr) = 0;
    // The alpha cache, for the application's own shaders that trace the field through foliage (bind it as a
    // storage buffer and include bricklight/alpha_cache.glsl): always a live buffer, whose header says whether the
    // context keeps a cache (a 16-byte stand-in without ContextFlags::AlphaCache). Owned by the context.
    virtual rhi::BufferHandle alphaCacheBuffer() const = 0;
    // Rays through the alpha cache, since the context was created, that met their tracer's bound on cards passed
    // and took the next alpha-tested hit as opaque without asking the cache (docs/gi.md, "Foliage": the GI's rays
    // pass at most 6 cards, hybrid shadow rays 6 layers): where many do, foliage there shades too dark. Counted by
    // every tracer bound to alphaCacheBuffer() (the GI's, the shadow classifier's, yours through
    // blAlphaCacheCountBoundReached); 0 without ContextFlags::AlphaCache. A blocking read-back.
    virtual uint64_t raysAtAlphaBound() = 0;
};

}  // namespace bricklight::gi
