// Bricklight voxel cone tracing (VXGI-class): the clip-map — a stack of levels of equal resolution, each twice
// the voxel size of the one below, centred on an anchor the application moves, addressed toroidally so that
// moving the anchor revoxelizes only the slabs that entered; voxelization of opacity and emittance through the
// application's own draws (a DrawCallState with our geometry and fragment shaders, to which the application
// adds its vertex shader and meshes), the coarser levels' inner parts downsampled from the finer ones; and
// cone tracing of diffuse, specular and ambient light from a G-buffer (ConeTracer) or from the application's
// shaders (bricklight/cone_trace.glsl). docs/vct.md.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bricklight/errors.h"
#include "bricklight/memory_use.h"
#include "bricklight/gbuffer/inputs.h"
#include "bricklight/rhi.h"
#include "bricklight/memory_use.h"
#include "bricklight/sdf.h"

namespace bricklight::vct {

constexpr uint32_t kMinLevels = 2, kMaxLevels = 8;

// How the light surfaces send is stored: not at all (voxel AO), one RGB value per voxel, or one per face
// direction (+X, +Y, +Z, −X, −Y, −Z; VXGI's anisotropic emittance, which keeps a wall lit on one side from
// lighting the other).
enum class EmittanceMode : uint8_t { None, Isotropic, Anisotropic };
// Directions whose radiance a voxel stores: 0, 1 or 6.
uint32_t emittanceDirections(EmittanceMode mode);

struct ClipmapDesc {
    uint32_t levels = 5;             // stack levels, kMinLevels..kMaxLevels (VXGI 2.0 in UE4: 128³ × 5)
    uint32_t resolution = 128;       // voxels per axis of every level: 32, 64, 128 or 256
    float finestVoxelSize = 0.08f;   // world units; level L's voxels are finestVoxelSize × 2^L
    // Coarser mips of the last level above the stack (each halves its resolution; cones wider than the
    // coarsest level's voxels read them instead of undersampling it); 0: log2(resolution) − 2, down to 4³, as
    // VXGI does.
    uint32_t mipLevels = 0;
    EmittanceMode emittance = EmittanceMode::Anisotropic;
    // Keep voxels from frame to frame and rewrite only what entered a level or was invalidated (VXGI's
    // persistentVoxelData); false: every update() clears and rewrites every level.
    bool persistent = true;
    // Light is summed in fixed point, 65536 × emittanceStorageScale units per unit of radiance in 32-bit words: raise
    // it for dim scenes, lower it where a voxel gathers more than ~60000 / scale.
    float emittanceStorageScale = 1.0f;
    // Voxel directions (a voxel's light towards one of the six directions, or its one isotropic value) whose light
    // one update can gather: 16 bytes each, claimed as the voxelization first writes them; at most 2^24. 0: an eighth
    // of the clip-map's voxels, at least 65536, at most 2^24 (a full revoxelization of our scenes at 128³ × 5 claims
    // 2–4 % of the voxels). Past it light is dropped and counted (VoxelizationCounters::lightDropped).
    uint64_t lightEntries = 0;
    // Multiple bounces (bricklight/voxelize.glsl's BL_VOXEL_MULTI_BOUNCE): a copy of the atlas made at the end of
    // each finishVoxelization(), which the next frame's voxelization reads (bounceBindings) while it writes the
    // atlas. Needs emittance; doubles the atlas's memory. With persistent = false every voxel's light follows.
    bool multiBounce = false;
};

// False with *error naming the field and the problem for a description no clip-map can have.
bool checkClipmapDesc(const ClipmapDesc& desc, Error* error = nullptr);
// The mip count a description asks for (resolving 0).
uint32_t clipmapMipLevels(const ClipmapDesc& desc);

// A box of voxels of one level in world voxel coordinates (voxel v of level L covers
// [v, v + 1) × finestVoxelSize × 2^L in world units): min inclusive, max exclusive.
struct VoxelBox {
    glm::ivec3 min{0}, max{0};
    uint64_t voxelCount() const;
};

// Where a level lies after an anchor move, and what of it must be voxelized because it entered the level.
struct LevelUpdate {
    uint32_t level = 0;
    glm::ivec3 origin{0};          // world voxel coordinates of the level's lowest corner
    std::vector<VoxelBox> entered;  // disjoint; the whole level when it moved by a level's width or more
};

// The levels' placement around the anchor (CPU side; the voxelization passes take it as constants).
// Each level's origin is an even number of its own voxels, so that every voxel of level L+1 is exactly 2³
// voxels of level L (downsampling reads whole voxels), and the levels nest: level L lies inside level L+1.
class ClipmapPlacement {
public:
    // Null with *error for a bad description. No level is placed until the first moveAnchor().
    static std::optional<ClipmapPlacement> create(const ClipmapDesc& desc, Error* error = nullptr);
    // Centres every level on `anchor` (snapped to its grid; non-finite anchors are refused with *error and
    // change nothing). Returns each level's new origin and the boxes that entered it: everything on the
    // first call or after invalidate(); then only the slabs the move uncovered (nothing if the snapped
    // origin did not change).
    std::optional<std::vector<LevelUpdate>> moveAnchor(const glm::vec3& anchor, Error* error = nullptr);
    // The next moveAnchor() revoxelizes every level in full.
    void invalidate() { placed_ = false; }
    bool placed() const { return placed_; }

    const ClipmapDesc& desc() const { return desc_; }
    float voxelSize(uint32_t level) const;  // world units
    glm::ivec3 origin(uint32_t level) const { return origins_[level]; }
    bool contains(uint32_t level, const glm::ivec3& voxel) const;
    // The texel of a level's volume that holds a world voxel: each axis modulo the resolution (positive),
    // so a voxel keeps its texel while the level scrolls over it.
    glm::ivec3 toroidalTexel(const glm::ivec3& voxel) const;
    // The world voxel of `level` that holds a point.
    glm::ivec3 voxelAt(uint32_t level, const glm::vec3& point) const;

private:
    explicit ClipmapPlacement(const ClipmapDesc& desc) : desc_(desc) {}
    ClipmapDesc desc_;
    std::vector<glm::ivec3> origins_;
    bool placed_ = false;
};

using MemoryUse = bricklight::MemoryUse;

// A box of one level's world voxels.
struct LevelBox {
    uint32_t level = 0;
    VoxelBox box;
};
// An axis-aligned box in world units (moved objects, changed lights).
struct WorldBox {
    glm::vec3 min{0.0f}, max{0.0f};
};

// What one voxelization draw of the application's meshes writes (VXGI's MaterialInfo).
struct VoxelMaterial {
    // Voxels of the level being written added along the projection axis behind the surface (half each side
    // for two-sided materials), 0..2. With 0 a wall is only the voxels it touches, often one, which a cone's filtered samples
    // see half transparent; 1 (VXGI's default) makes it two, which they see opaque.
    float thickness = 1.0f;
    // Emits from both sides (the hook runs twice, the second time with the normal flipped).
    bool twoSided = false;
    // 0..1: how much of a voxel's cross-section the surface blocks. Alpha-tested materials (foliage) keep 1 and
    // give their coverage per point in the shaders instead (BL_VOXEL_COVERAGE, docs/vct.md "Foliage"); this
    // constant multiplies it.
    float opacity = 1.0f;
    // The application's voxelization fragment shader (bricklight/voxelize.glsl with its blVoxelEmittance, and
    // blVoxelCoverage for an alpha-tested material); null: ours, opacity only.
    rhi::ShaderHandle fragmentShader;
    // The same blVoxelEmittance as a compute shader (bricklight/voxelize_compute.glsl), for vct::VoxelScene's
    // compute voxelizer, which draws the triangles too big for one invocation with fragmentShader: it needs
    // fragmentShader too. Null: ours (opacity only) where fragmentShader is null too; an instance with a
    // fragmentShader and no computeShader is drawn, so that no emittance is lost. Ignored by draws.
    rhi::ShaderHandle computeShader;
};
// False with *error naming the field for a material no draw can use.
bool checkVoxelMaterial(const VoxelMaterial& material, Error* error = nullptr);

// The binding slots a voxelization record uses; the application's own bindings (its vertex shader's and its
// emittance function's) must use others.
namespace VoxelizationSlots {
constexpr uint8_t kMaterialConstants = 3;  // BL_CONSTANTS
constexpr uint8_t kFrameReadBuffer = 7;    // BL_READ_BUFFER
constexpr uint8_t kLightBuffer = 6;        // BL_STORAGE_BUFFER
constexpr uint8_t kCountersBuffer = 7;     // BL_STORAGE_BUFFER
constexpr uint8_t kAtlasImage = 7;         // BL_IMAGE
}  // namespace VoxelizationSlots

// Validation counters of the voxelization fragment shader (VXGI's scissor statistics), summed over the draws
// since resetCounters().
struct VoxelizationCounters {
    uint64_t fragments = 0;        // fragments shaded
    uint64_t offTriangle = 0;      // fragments of the dilated quad whose pixel does not touch the triangle
    uint64_t voxelsWritten = 0;    // opacity writes
    uint64_t killedByFiner = 0;    // voxels inside the finer level (downsampled instead)
    uint64_t killedNotDirty = 0;   // voxels outside this update's rewrite boxes
    uint64_t emittanceWrites = 0;  // voxels that received emittance
    // Always counted, since the latest update(): light entries claimed (of the pool's, ClipmapDesc::lightEntries)
    // and light writes dropped because the pool was full.
    uint64_t lightEntriesClaimed = 0, lightEntriesAvailable = 0;
    uint64_t lightDropped = 0;
};

// Debug views of the clip-map (Clipmap::debugView): the first voxel at least a quarter opaque along each pixel's
// ray, shown as its opacity along x, y, z (rgb); the light it sends (back along the ray, or towards
// `direction`); its level (red, orange, yellow, green, cyan, blue, violet, white from the finest); or whether
// this update rewrote it (red) or kept it (grey).
enum class DebugMode : uint32_t { Opacity, Emittance, Level, Rewritten };
struct DebugViewDesc {
    DebugMode mode = DebugMode::Opacity;
    int32_t level = -1;      // the level to show (levels, then the coarsest level's mips); −1: the finest that holds each point
    int32_t direction = -1;  // emittance: 0..5 (+X, +Y, +Z, −X, −Y, −Z); −1: back along the ray
    glm::mat4 view{1.0f}, projection{1.0f};  // the camera (GiContext's conventions)
    glm::vec3 cameraPosition{0.0f};
    rhi::TextureHandle output;  // RGBA8_UNORM with Storage usage
    float exposure = 1.0f;      // emittance: radiance scale before tone mapping
};

// Bytes a description needs on the device (what memoryUse() will report), for sizing before creating.
uint64_t clipmapBytes(const ClipmapDesc& desc);

// The clip-map's volumes on a device, kept in step with the placement, and the voxelization that fills them.
//
//   resource             format / layout                          holds
//   vct atlas            R32_UINT 3D, regions × (res + 2) wide,   regions side by side in x: opacity along x, y, z
//                        res high, levels × (res + 2) +           (8 bits each; sampled as RGBA8_UNORM), then the
//                        res / 2 + 3 deep                         radiance of each direction (RGB9E5 bits; sampled as
//                                                                 RGB9E5_FLOAT); level L in z slices [L·(res+2), …),
//                                                                 a world voxel at its coordinates modulo res
//                                                                 (toroidal) with border columns and slices, then the
//                                                                 coarsest level's mips (bricklight/vct_layout.glsl).
//                                                                 The voxelization writes opacity in place (atomic
//                                                                 maximum); a direction's word holds its light
//                                                                 entry's tagged index until finishVoxelization().
//   vct light            buffer, 4 words × lightEntries           fixed-point light and coverage sums of one update's
//                                                                 voxel directions (zeroed as they are read)
//   vct atlas (bounce)   the same, multiBounce only               a copy of the previous frame's, read by bounce cones
//   vct no bounce        R32_UINT 1³, without multiBounce         a zero stand-in for bounceBindings
//   vct frame            read buffer (origins, boxes)             what update() decided, read by the draws
//   vct counters         storage buffer, 8 words                  VoxelizationCounters
//   vct raster size      D32 resolution², never written           sets the draws' raster size (no colour targets)
//
// A frame: update(anchor, invalidated) → the application draws its meshes with voxelizationState(material)
// (all of them, or those touching dirtyRegions()) → finishVoxelization().
class Clipmap {
public:
    // Null with *error for a bad description or a device that cannot create the volumes.
    static std::unique_ptr<Clipmap> create(rhi::IDevice& device, const ClipmapDesc& desc, Error* error = nullptr);
    ~Clipmap();
    Clipmap(const Clipmap&) = delete;
    Clipmap& operator=(const Clipmap&) = delete;

    // Moves the anchor (ClipmapPlacement::moveAnchor), decides which voxels this frame rewrites — what
    // entered a level, what left the finer level inside it, and the `invalidated` boxes (moved objects,
    // changed lights), or everything when the clip-map is not persistent — and records their clears. A refused
    // anchor or a non-finite box changes and records nothing.
    std::optional<std::vector<LevelUpdate>> update(const glm::vec3& anchor, Error* error,
                                                   const std::vector<WorldBox>& invalidated = {});
    // The next update() rewrites every level whole.
    void invalidate() { placement_.invalidate(); }

    // The draw record for one material: our geometry shader (one invocation per level, dominant-axis projection,
    // dilated by half a voxel) and fragment shader (material.fragmentShader or ours), the clip-map's bindings,
    // a resolution² raster and no colour targets. The application sets vertexShader (writing
    // bricklight/voxelize_vertex.glsl's outputs), vertexInputs, vertexBuffers, indexBuffer and topology
    // (triangles), may add bindings in slots other than VoxelizationSlots, and draws. The record stays valid
    // across frames while this clip-map lives. Null with *error for a bad material or a device without
    // geometry shaders.
    std::optional<rhi::DrawCallState> voxelizationState(const VoxelMaterial& material, Error* error = nullptr);
    // After this frame's draws: fills the coarser levels' inner voxels that this frame changed from the finer
    // levels (shaders/vct/downsample.comp), the border columns and slices of the levels that changed
    // (borders.comp) and the coarsest level's mips when it changed (mip_build_*.comp).
    void finishVoxelization();

    // For an application's shader that includes bricklight/cone_trace.glsl: the atlas's two views at texture slots
    // textureBase and textureBase + 1 (with a linear sampler that wraps in y) and the frame buffer at read buffer
    // slot frameSlot (the include's defaults: 8 and 7). Added to `bindings` (the frame buffer only if absent).
    void traceBindings(rhi::Bindings& bindings, uint8_t textureBase = 8, uint8_t frameSlot = 7) const;
    // The same for a voxelization record whose fragment shader uses BL_VOXEL_MULTI_BOUNCE: the copy of the previous
    // frame's atlas with ClipmapDesc::multiBounce, a zero stand-in without (the bounce cones then gather nothing).
    // The atlas being written cannot be read by the same draw.
    void bounceBindings(rhi::Bindings& bindings, uint8_t textureBase = 8, uint8_t frameSlot = 7) const;

    // The boxes this frame's draws may write (fragments elsewhere are dropped), and the same as world boxes
    // for culling the draws.
    const std::vector<LevelBox>& rewriteBoxes() const { return rewrite_; }
    std::vector<WorldBox> dirtyRegions() const;

    // Records a debug view (DebugMode) into desc.output; false with *error, recording nothing, for a bad
    // description.
    bool debugView(const DebugViewDesc& desc, Error* error = nullptr);

    void setCountersEnabled(bool enabled);
    void resetCounters();
    VoxelizationCounters readCounters();  // waits for the GPU (tests and tools)

    const ClipmapPlacement& placement() const { return placement_; }
    const ClipmapDesc& desc() const { return placement_.desc(); }
    // The atlas (the resource table and bricklight/vct_layout.glsl).
    rhi::TextureHandle atlas() const { return atlas_[0]; }
    MemoryUse memoryUse() const;

private:
    Clipmap(rhi::IDevice& device, const ClipmapPlacement& placement) : device_(device), placement_(placement) {}
    void clearBox(const LevelBox& box);
    void resolveBox(const LevelBox& box);
    void downsampleBox(const LevelBox& box);
    void copyBorders(uint32_t level);
    void buildMips();
    void bindAtlas(rhi::Bindings& bindings, rhi::TextureHandle atlas, uint8_t textureBase, uint8_t frameSlot) const;
    void writeFrame();
    struct MaterialBlock {
        float values[4];
    };
    rhi::IDevice& device_;
    ClipmapPlacement placement_;
    rhi::ShaderHandle clearBoxes_, resolve_, downsample_, borders_, mipBuild_, voxelizeGeometry_, voxelizeOpacity_, debugView_;
    rhi::TextureHandle atlas_[2], noBounce_, rasterSize_;  // atlas_[1]: the bounce copy (multiBounce)
    rhi::SamplerHandle tracedSampler_;
    rhi::BufferHandle light_, frame_, counters_;
    std::vector<LevelBox> rewrite_, downsampleBoxes_;
    std::vector<std::unique_ptr<MaterialBlock>> materials_;  // stable addresses for the records' constants
    bool countersEnabled_ = false;
};

// Cone tracing parameters (VXGI's CommonTracingParameters, DiffuseTracingParameters, SpecularTracingParameters).
struct ConeTraceParams {
    uint32_t diffuseCones = 8;      // 1..32 cones over the hemisphere, cosine-weighted
    float diffuseConeAngle = 0.0f;  // full angle in radians; 0: from the count (each cone covers 2π / cones sr)
    uint32_t tracingSparsity = 2;   // 1..4: diffuse cones traced for one pixel per N×N block (another each frame)
    // 0.25..1: diffuse cones' sample spacing / sample diameter (smaller: smoother, slower). VXGI's 0.5 suits
    // opacity compounded per step (Beer); here the shares of one crossing add, and reads one sample width apart
    // still sum a wall's trilinear spread whole, so 1 keeps the light (docs/vct.md, *Speed*) at half the samples.
    float tracingStep = 1.0f;
    float specularTracingStep = 1.0f;  // the same for the specular cone (VXGI's defaults: 0.5 diffuse, 1 specular)
    float opacityCorrection = 1.0f; // 0.1..10: scales the opacity each step takes (higher: darker, more contrast)
    uint32_t lightLeakLag = 0;      // 0..2: samples the transmittance lags (VXGI 1.0 used 2; 0 leaks least)
    float initialOffset = 2.0f;     // voxels (of the level at the surface) along the normal before the first sample
    float maxDistance = 0.0f;       // world units a cone may go; 0: until it leaves the clip-map
    float ambientRange = 0.0f;      // world units: ambient = transmittance at this distance; 0: 8 finest voxels
    float temporalWeight = 0.85f;   // 0..0.98: the reprojected history's share (0: off)
    float maxSpecularRoughness = 0.75f;  // roughness is clamped to this for the specular cone's width
    // 0..1: the specular cone narrows by half this and its axis wanders over the wide cone's width from frame to
    // frame (tangent jitter; the temporal blend averages it). 0: off — the narrower cone takes twice the samples,
    // about twice the specular pass's time, for a small gain (glossy floor relMSE 0.0283 → 0.0280; docs/vct.md).
    float specularJitter = 0.0f;
};
// False with *error naming the field for parameters no trace can use.
bool checkConeTraceParams(const ConeTraceParams& params, Error* error = nullptr);

// One frame's cone tracing from the application's G-buffer. The conventions are GiContext's (gi.h,
// DispatchDesc): depth [0, 1] with 1 the far plane, NDC y = −1 at the top row, world-space normals
// (unpacked as n · scale + offset), motion vectors as UV (current − previous).
struct TraceDesc {
    gbuffer::Camera camera;                    // bricklight/gbuffer/inputs.h
    bricklight::gbuffer::Inputs gbuffer;       // depth, normals, roughness, motion
    glm::vec3 cameraPosition{0.0f};
    // RGBA16_FLOAT, display size, Storage. Diffuse: rgb irradiance / π (before albedo), a ambient (1 open);
    // specular (optional; refused on a clip-map without emittance, which has no light): rgb prefiltered radiance along
    // the mirror direction.
    rhi::TextureHandle outputDiffuse, outputSpecular;
    ConeTraceParams params;
    bool resetHistory = false;  // a camera cut: forget the reprojected history
    // Optional: a distance field of the same scene. Each cone then traces one ray along its axis through the
    // field (exact distances) and stops where that ray meets a surface: samples more than half their width past
    // it add nothing. That keeps cones from leaking through walls thinner than the coarse voxels they sample,
    // and costs a wide cone the light an object on its axis does not hide. Where the field has no answer
    // (outside its cascades, out of iterations) the cone goes on as without it. The field must be updated.
    const sdf::SdfScene* occlusionField = nullptr;
};

// One sample of a recorded cone (ConeTracer::debugConeSamples).
constexpr uint32_t kSpecularCone = 32;      // ConeSample::cone of the specular cone (diffuse cones: 0..31)
constexpr uint32_t kSurfaceSample = 255;    // ConeSample::level of the surface read where the distance field stopped the cone
constexpr uint32_t kMaxConeSamples = 64;    // samples recorded per cone (a longer cone's are cut)
struct ConeSample {
    glm::vec3 position{0.0f};    // world
    float diameter = 0.0f;       // world
    glm::vec3 light{0.0f};       // the radiance the sample added to its cone
    float transmittance = 1.0f;  // the cone's before the sample
    uint32_t level = 0;          // the finer of the two levels sampled, or kSurfaceSample
    uint32_t cone = 0;
};

constexpr uint32_t kAutomaticRefinement = 0xFFFFFFFFu;  // ConeTracerDesc::refinementEntries: a quarter of the pixel count

struct ConeTracerDesc {
    uint32_t width = 0, height = 0;  // the G-buffer's size in pixels
    // The refinement's room, in cones (4 bytes each; a listed pixel takes its diffuse cone count): pixels that no sparse
    // sample fits trace their own cones in a pass of their own, one cone to an invocation, as long as their cones fit
    // (the rest in the resolve, one pixel's cones one after another, which made the pass wait on them). 0: all in the
    // resolve (docs/vct.md, Passes).
    uint32_t refinementEntries = kAutomaticRefinement;
};

// The tracing passes: sparse diffuse cones + geometry-aware upsample with refinement + temporal reprojection
// (shaders/vct/trace_diffuse.comp, resolve_diffuse.comp), one specular cone per pixel + temporal
// (trace_specular.comp). Reads what the clip-map's finishVoxelization() resolved. Without emittance
// (EmittanceMode::None) the diffuse output's rgb is zero and its alpha is the voxel ambient occlusion.
class ConeTracer {
public:
    // Null with *error for a zero size or a device that cannot create the history.
    static std::unique_ptr<ConeTracer> create(rhi::IDevice& device, const Clipmap& clipmap, const ConeTracerDesc& desc,
                                              Error* error = nullptr);
    ~ConeTracer();
    ConeTracer(const ConeTracer&) = delete;
    ConeTracer& operator=(const ConeTracer&) = delete;
    // Records the passes; false with *error (recording nothing) for missing or mis-sized inputs or bad parameters.
    bool dispatch(const TraceDesc& desc, Error* error = nullptr);
    // Debug: records the cones of pixel (x, y) as the latest dispatch() traced them (its diffuse cones of that
    // frame's turn, and its specular cone when it had a specular output) and draws their samples over the view —
    // spheres of each sample's width coloured by cone, darker by transmittance, the surface reads yellow, the pixel
    // marked — into `output` (RGBA8_UNORM, Storage, the tracer's size). The latest dispatch's inputs must still be
    // live. False with *error, recording nothing, before any dispatch or for a bad pixel or output.
    bool debugConeSamples(uint32_t x, uint32_t y, rhi::TextureHandle output, Error* error = nullptr);
    // The samples debugConeSamples recorded last, cone by cone (waits for the GPU; tests and tools).
    std::vector<ConeSample> readConeSamples();
    // How many pixels the latest dispatch() refined (no sparse sample fit them), those the refinement had no room for
    // included; reads the count back from the device (for tests and tools).
    uint32_t readRefinedPixels();
    MemoryUse memoryUse() const;

private:
    ConeTracer(rhi::IDevice& device, const Clipmap& clipmap) : device_(device), clipmap_(clipmap) {}
    rhi::IDevice& device_;
    const Clipmap& clipmap_;
    uint32_t width_ = 0, height_ = 0, frame_ = 0;
    uint32_t sparsity_ = 0;  // of the low-resolution textures as created
    rhi::ShaderHandle traceDiffuse_, resolveDiffuse_, traceSpecular_;
    rhi::ShaderHandle traceDiffuseSdf_, traceSpecularSdf_;  // the variants for TraceDesc::occlusionField
    rhi::ShaderHandle traceOcclusion_;  // the diffuse cones without light, for a clip-map without emittance
    rhi::ShaderHandle refineDiffuse_;  // the refinement's cones and blend (shaders/vct/refine_list.glsl)
    rhi::BufferHandle refineCounts_[2], refineList_;
    uint32_t refineEntries_ = 0;  // cones the refinement holds room for: refineList_'s words
    rhi::TextureHandle lowDiffuse_, lowGuide_;
    rhi::TextureHandle diffuseHistory_[2], specularHistory_[2], guide_[2];
    rhi::BufferHandle params_;
    rhi::SamplerHandle point_;
    std::optional<TraceDesc> latest_;  // the latest dispatch's description (debugConeSamples)
    rhi::ShaderHandle coneSamples_, coneSamplesSdf_, coneSamplesView_;  // cone_samples.cpp, created at first use
    rhi::BufferHandle coneSampleRecord_;
    bool bindLowResolution(uint32_t sparsity, Error* error = nullptr);
    void dispatchRefinement(const TraceDesc& desc);  // after the resolve, within frame_'s dispatch
    void bindCommon(rhi::Bindings& bindings, const TraceDesc& desc) const;  // the G-buffer, the clip-map, the parameters
    void bindField(rhi::Bindings& bindings, const TraceDesc& desc) const;   // the occlusion field, if any
};

}  // namespace bricklight::vct
