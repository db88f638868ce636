// The renderer's fast path: a G-buffer rasterized through DrawCallState records (albedo + roughness,
// normal, emission + metalness, motion vectors, depth), direct lighting from emitters, the sun and the
// sky with ray-traced shadows (examples/demo_renderer/shaders/direct_light.comp, the path tracer's estimator), then GI
// (gi::GiContext on an sdf::SdfScene of the scene) composited with it (examples/demo_renderer/shaders/composite.comp).
// Each frame's lit image feeds the next frame's GI, so bounces accumulate over frames.
#pragma once

#include <array>
#include <memory>
#include <string>

#include "bricklight/shadows/classifier.h"
#include "bricklight/gbuffer/depth_pyramid.h"
#include "bricklight/gi.h"
#include "bricklight/reflections/classifier.h"
#include "bricklight/reflections/denoiser.h"
#include "bricklight/sdf.h"
#include "bricklight/shadows/denoiser.h"
#include "bricklight/vct.h"
#include "display_view.h"
#include "gpu_scene.h"
#include "path_tracer.h"
#include "shadow_cascades.h"

namespace bricklight::render {

// Where the sun's visibility in the direct lighting comes from: a ray through the scene's BVH per pixel (exact;
// the default), or cascaded shadow maps (raster_renderer_shadows.cpp). Emitters, point lights and the sky keep
// their ray-traced estimator in both modes. docs/render.md, "Shadows".
// Bvh: the sun's visibility from BVH rays (the path tracer's estimator). ShadowMap: from cascaded shadow maps.
// Hybrid: the shadow maps classified per 8×4 tile (shadows::ShadowClassifier), rays through the distance field
// where they cannot decide.
enum class ShadowMode { Bvh, ShadowMap, Hybrid };

// The cascaded shadow maps' parameters (ShadowMode::ShadowMap). checkSunShadowOptions says what is accepted.
struct SunShadowOptions {
    uint32_t resolution = 1024;  // texels per side of each cascade's map (kMinShadowResolution..kMaxShadowResolution)
    float splitLambda = 0.75f;   // 0 uniform .. 1 logarithmic splits
    float shadowDistance = 0.0f;  // the cascades reach this far along the view (0: the scene bounds' farthest corner)
    float slopeBias = 1.5f;      // the rasterizer's slope-scaled depth bias in the shadow draws (0..16)
    float depthBias = 1.0f;      // the receiver's depth is moved this many texels towards the sun (0..16)
    float normalOffset = 1.0f;   // the receiver is moved this many texels along its normal (0..16)
    uint32_t pcfRadius = 1;      // PCF over (2·radius + 1)² bilinear taps (0..kMaxShadowPcfRadius)
};
// False with *error naming the field for parameters the shadow maps cannot use.
bool checkSunShadowOptions(const SunShadowOptions& options, std::string* error);

// The sun's cascades of the latest frame, for passes that read the shadow maps (the shadow classifier).
struct ShadowCascadesView {
    // D32_FLOAT 2D atlas of 2 × 2 tiles of resolution² texels: cascade i in tile shadowAtlasTile(i); null in Bvh
    // mode. Depth 0 nearest the sun, cleared to 1 (no caster).
    rhi::TextureHandle depth;
    std::array<ShadowCascade, kShadowCascades> cascades{};  // viewProjection: world → the map's clip space
    uint32_t resolution = 0;
    glm::vec3 sunDirection{0.0f};  // towards the sun
};

// Where glossy reflections come from (with the SDF GI): Gi, the GI's specular output alone; Hybrid, the reflection
// classifier's screen-space and distance-field rays, denoised, over the GI's specular where they resolved
// (raster_renderer_reflections.cpp; docs/render.md, "Reflections").
enum class ReflectionMode { Gi, Hybrid };

// Which technique gives the indirect light when RasterOptions::gi is on.
enum class GiTechnique { Sdf, Vct };

// How the GI sees alpha-tested meshes (foliage; docs/gi.md and docs/vct.md, "Foliage"). The SDF GI: AlphaAware
// registers them as alpha-tested and runs the GI's alpha pass, so that its rays go on past the cut-out texels;
// Opaque builds the cards into the field as solid; LeftOut leaves them out of the field. Voxel cone tracing:
// AlphaAware weighs their voxels' opacity and light by their coverage; Opaque voxelizes them as solid cards;
// LeftOut does not voxelize them. Left out, they are still drawn and lit (they only receive GI). The two naive
// variants are kept for comparison.
enum class FoliageMode { AlphaAware, Opaque, LeftOut };

struct RasterOptions {
    uint32_t width = 256, height = 256;
    uint32_t lightSamples = 16;  // emitter (and sky) samples per pixel for direct lighting, each frame
    // The direct light is a running mean over at most this many frames, reprojected per surface point
    // (raster_renderer_direct_history.cpp); 1: each frame's own lightSamples only.
    uint32_t directFrames = 1024;
    uint32_t seed = 1;
    bool gi = false;  // true: GI from the distance field (bricklight-render turns it on)
    gi::InternalResolution giResolution = gi::InternalResolution::Native;
    bool giRelight = true;  // give GI the albedo, emission and lights, so it re-lights what the camera does not see
    // The lit image GI injects next frame holds GI too, so bounces accumulate over frames; false: direct
    // light only, so GI is exactly one bounce (to compare with the path tracer's maxBounces = 1).
    bool giFeedback = true;
    uint32_t giCacheBricks = 0;  // gi::ContextDesc::radianceCacheBricks (0: the default)
    uint32_t giInjectTile = 0;   // gi::ContextDesc::injectTile (0: automatic)
    uint32_t giProbeTile = 0;    // gi::ContextDesc::probeTile (0: automatic)
    uint32_t giFlags = 0;        // gi::ContextFlags added to those the renderer sets itself
    gi::TraceParams giTrace;            // gi::DispatchDesc::trace (live: setGiTuning)
    float giRoughnessThreshold = 0.75f;  // gi::DispatchDesc::roughnessThreshold (live)
    GiTechnique giTechnique = GiTechnique::Sdf;
    FoliageMode foliage = FoliageMode::AlphaAware;
    // Voxel cone tracing (giTechnique Vct, or vxao): the clip-map is centred on the scene; its finest level
    // holds the scene's bounds with a margin, each next level doubles.
    uint32_t vctResolution = 64, vctLevels = 5;
    // The finest level's voxel size in world units (> 0); 0: as large as holding the scene in the finest level
    // asks. Smaller voxels resolve smaller things (grass a voxel tall is one layer) near the scene's centre.
    float vctFinestVoxel = 0.0f;
    vct::EmittanceMode vctEmittance = vct::EmittanceMode::Anisotropic;
    uint32_t vctLightSamples = 4;  // light samples per voxelization fragment
    float vctThickness = 1.0f;     // vct::VoxelMaterial::thickness of every surface (two-sided: half each side)
    vct::ConeTraceParams vctTrace;
    uint32_t vctRefinementEntries = vct::kAutomaticRefinement;  // vct::ConeTracerDesc::refinementEntries
    // Cones stop at the first surface the distance field's ray meets along their axis (vct::TraceDesc::
    // occlusionField): the renderer builds the field for voxel cone tracing too.
    bool vctSdfOcclusion = false;
    // With the SDF GI (giTechnique Sdf): a clip-map with emittance is voxelized each frame, and GI's probe rays
    // that hit surfaces the camera never saw read its light (gi::DispatchDesc::unseenLight).
    bool giUnseenFromVct = false;
    // With the SDF GI: probe rays light the surfaces no view has lit (gi::DispatchDesc::lightUnseenSurfaces) in every
    // scene, with a sky too (GI is given it as its environment, environmentInDirectLight). Without it they do so only
    // where the lights hold all of the direct light (no sky), and elsewhere take the stand-in (docs/gi.md).
    bool giUnseenPath = false;
    // Voxel ambient occlusion (an opacity-only clip-map) when GI does not already trace cones: the AO image is
    // readAmbientOcclusion(); it does not change the lit image (direct lighting already shadows the sky).
    bool vxao = false;
    uint32_t sdfCascades = 3;  // the finest covers the scene's bounds; each next one doubles
    sdf::Budgets sdfBudgets;   // the distance field's per-update budgets (deferred work goes to later updates)
    ShadowMode shadows = ShadowMode::Bvh;
    ReflectionMode reflections = ReflectionMode::Gi;
    float reflectionRoughness = 0.4f;  // Hybrid: perceptual roughness from which pixels keep the GI's specular
    SunShadowOptions sunShadows;
    // Build the hierarchical depth pyramid of the G-buffer depth each frame (depthPyramid()); off, it costs nothing.
    bool depthPyramid = false;
    // Receives the SDF's and GI's messages (stderr when empty): an application counts them as it counts its
    // device's.
    rhi::ErrorCallback errorCallback;
};

// The G-buffer and camera of the latest frame, for tools that drive GI themselves (the benchmark).
struct GBufferView {
    rhi::TextureHandle albedo, normal, emission, motion, position, depth, lit;
    glm::mat4 view{1.0f}, projection{1.0f}, previousView{1.0f}, previousProjection{1.0f};
    glm::vec3 eye{0.0f};
};

// The scene's sun, point/spot lights and emitting surfaces as the GI relights what the camera does not see
// (raster_renderer_gi.cpp). emittersInLights: every emitting triangle is among the lights (at most
// gi::kMaxLights lights in all; else the emitters are left to the relight rays).
struct GiLights {
    std::vector<gi::Light> lights;
    bool emittersInLights = false;
    bool allDirectLight = false;  // the lights hold all the direct light: the emitters, and no sky (GI's environment)
    glm::vec3 sky{0.0f};          // the sky's radiance: GI's environment, which the direct lighting holds
};

class RasterRenderer {
public:
    static std::unique_ptr<RasterRenderer> create(rhi::IDevice& device, const scenes::SceneGeometry& scene,
                                                  const RasterOptions& options, std::string* error);
    ~RasterRenderer();
    // The next frame's camera; the previous one gives the motion vectors.
    bool setCamera(const scenes::Camera& camera, std::string* error);
    // The scene of the next frame (an animated scene's next state): its vertices' previous positions are
    // this frame's, for motion vectors. Fails, changing nothing, on a bad scene.
    bool setScene(const scenes::SceneGeometry& scene, std::string* error);
    void render();  // records one frame: the ordered list of passes in raster_renderer.cpp
    // Combined (direct + GI), direct, indirect-diffuse (GI's diffuse output; zero without GI), albedo,
    // normal, depth.
    Image read(Aov aov);
    Image readSpecularGi();  // GI's specular output (zero without GI)
    // Voxel ambient occlusion (1 open) in every channel: from the cone tracer's diffuse alpha (--gi vxgi or
    // vxao); empty without voxel cone tracing.
    Image readAmbientOcclusion();
    // A voxel cone tracing debug view of the latest frame (0..1, from the camera); empty without a clip-map.
    Image vctDebugView(vct::DebugMode mode, float exposure);
    // The samples of the probe pixel's cones in the latest frame drawn over the view (View::VctConeSamples), and
    // the samples themselves; empty without the cone tracer.
    Image vctConeSamplesView();
    std::vector<vct::ConeSample> vctConeSamples();
    // The pixels the latest frame's cone tracer refined (vct::ConeTracer::readRefinedPixels); 0 without it.
    uint32_t vctRefinedPixels();
    // The pixel whose cones View::VctConeSamples shows (default: the centre; clamped to the image).
    void setVctProbePixel(uint32_t x, uint32_t y) { probePixel_ = glm::uvec2(x, y); }
    // A GI debug view of the latest frame (tone-mapped, 0..1); empty without GI.
    Image giDebugView(gi::DebugMode mode, float exposure);
    GBufferView gbuffer() const;
    // Draws `view` of the latest frame into `rect` of `display` (RGBA8_UNORM with Storage usage: a window's
    // picture), scaled to the rectangle by nearest neighbour; radiance is mapped as image files are
    // (exposure, filmic, sRGB). False with *error, drawing nothing, when the view needs GI and GI is off or
    // the display texture or rectangle is unfit. (raster_renderer_display.cpp)
    bool drawView(View view, rhi::TextureHandle display, const DisplayRect& rect, float exposure, std::string* error);
    gi::GiContext* giContext() { return gi_.get(); }
    vct::Clipmap* clipmap() { return clipmap_.get(); }
    sdf::SdfScene* sdfScene() { return sdf_.get(); }
    // GI's tracing parameters from the next frame on (the rest of RasterOptions is fixed at creation).
    void setGiTuning(const gi::TraceParams& trace, float roughnessThreshold) {
        options_.giTrace = trace;
        options_.giRoughnessThreshold = roughnessThreshold;
    }
    // Voxel cone tracing's parameters from the next frame on (refused ones are reported and skipped then).
    void setVctTuning(const vct::ConeTraceParams& trace) { options_.vctTrace = trace; }
    const RasterOptions& options() const { return options_; }
    glm::vec3 sdfCenter() const { return sdfCenter_; }
    // The distance field's cascades follow this point from the next frame on (default: the scene's centre).
    void setSdfCenter(const glm::vec3& center) { sdfCenter_ = center; }
    glm::vec3 sceneCenter() const { return sceneCenter_; }
    // The renderer's own GPU resources (G-buffer, lighting buffers, GI outputs) and their bytes.
    sdf::MemoryUse memoryUse() const;
    // The next frame starts a new shot: GI forgets its screen history.
    void cameraCut() { cut_ = true; }
    Image readMotion();  // rg = UV motion (current - previous), b = 0
    uint32_t triangleCount() const { return scene_->triangleCount(); }
    // Pixels and fragments of the frames so far whose ray-traced lighting (direct light, BVH shadows, glass,
    // voxelization's light) a CPU driver's limit on loop iterations cut short, leaving it wrong: rays through
    // thousands of overlapping triangles. Zero on GPUs. A blocking read-back (GpuScene::invocationsCutShort).
    uint64_t invocationsCutShort() const { return scene_->invocationsCutShort(); }
    // The sun's shadow cascades of the latest frame (ShadowMode::ShadowMap or Hybrid; depth null otherwise).
    ShadowCascadesView shadowCascades() const;
    // The sun's visibility the direct lighting used in the latest frame (0..1 in every channel, 0 where the
    // surface faces away from the sun, 1 on the sky); empty with ShadowMode::Bvh.
    Image readSunVisibility();
    // The G-buffer depth's min/max pyramid of the latest frame (RasterOptions::depthPyramid); null when off.
    const gbuffer::DepthPyramid* depthPyramid() const { return depthPyramid_.get(); }
    // ShadowMode::Hybrid: the classifier of the latest frame (its tile list, counts and hit mask); null otherwise.
    shadows::ShadowClassifier* shadowClassifier() { return shadowClassifier_.get(); }
    // ReflectionMode::Hybrid: the reflection classifier of the latest frame (its lists, counts and debug view) and the
    // denoised reflections (rgb, a = weight over GI's specular); null otherwise.
    reflections::ReflectionClassifier* reflectionClassifier() { return reflectionClassifier_.get(); }
    Image readReflections();  // the denoised reflections (rgb) of the latest frame; empty when off
    // One of the hybrid reflections' views (View::Reflections.. the tile views; 0..1 for the tile views); empty when off.
    Image reflectionView(View view);

private:
    explicit RasterRenderer(rhi::IDevice& device) : device_(device) {}
    // This frame's camera (and the previous one) and G-buffer as every technique's description takes them
    // (bricklight/gbuffer/inputs.h): float normals, roughness in the albedo target's alpha, UV motion.
    gbuffer::Camera frameCamera() const;
    gbuffer::Inputs frameGBuffer() const;
    // The frame's passes not owned by a technique (raster_renderer.cpp).
    void drawGBuffer();
    void buildDepthPyramid();
    SceneLightConstants lightDirect();
    // raster_renderer_direct_history.cpp: the direct light's running mean over frames.
    bool createDirectHistory(std::string* error);
    void destroyDirectHistory();
    void accumulateDirectLight(const SceneLightConstants& light, bool cut);
    void composite();
    void shiftCameraHistory();
    // raster_renderer_sdf.cpp: the field, its one update a frame and the GI's alpha pass after it.
    bool createSdf(const scenes::SceneGeometry& scene, std::string* error);  // the distance field alone
    void updateDistanceField();  // before the direct light: hybrid shadows, GI and SDF-stopped cones read it
    // raster_renderer_gi.cpp
    bool createGi(const scenes::SceneGeometry& scene, std::string* error);   // the field (if not yet) and GI
    void dispatchGi(bool cut);
    // raster_renderer_vct.cpp
    bool createVct(const scenes::SceneGeometry& scene, std::string* error);
    void voxelizeVct();        // before GI, which may read the clip-map's light (giUnseenFromVct)
    void traceVct(bool cut);   // the cone tracer's passes, after GI's
    bool giOn() const { return gi_ || (clipmap_ && options_.vctEmittance != vct::EmittanceMode::None); }
    // Glass (raster_renderer_glass.cpp): with a clip-map that holds light, meshes with transmission > 0 are left
    // out of the G-buffer and the voxelization and drawn by a forward pass that traces cones through them.
    bool glassPassOn() const;
    uint32_t rasterTriangleCount() const;  // what the G-buffer and the voxelization draw (the opaque range, or all)
    bool createGlass(std::string* error);  // the pass's shader and a placeholder target the composite can bind
    void renderGlass();                     // before the composite, which takes the glass pixels from it
    void syncSdf(const scenes::SceneGeometry& scene);
    // raster_renderer_shadows.cpp: the shadow maps' shaders and textures (a 1×1 placeholder in Bvh mode, which
    // the direct lighting binds but does not read), their draws, and the constants the direct lighting takes.
    bool createShadows(const scenes::SceneGeometry& scene, std::string* error);
    void renderShadowMaps();
    void destroyShadows();
    void setSun(const scenes::SceneGeometry& scene);  // the sun and the scene's bounds the cascades span
    // ShadowMode::ShadowMap: adds the sun, shadowed by the maps, to the direct lighting (shadow_sun_light.comp);
    // Hybrid: shadowed by the classifier's shadow mask (shadow_sun_light_hybrid.comp), after classifyShadows().
    void lightSunFromShadowMaps(const SceneLightConstants& light);
    bool mapsOn() const { return options_.shadows == ShadowMode::ShadowMap || options_.shadows == ShadowMode::Hybrid; }
    void classifyShadows();  // Hybrid: the classification, the rays through the field and the shadow mask
    uint32_t hybridShadowFinerCascades() const;  // Hybrid: cascades the field adds below its finest, around the camera
    std::unique_ptr<shadows::ShadowClassifier> shadowClassifier_;
    rhi::TextureHandle sunMask_;  // Hybrid: R16F, 1 lit
    // Hybrid with a sun of angular size: soft rays (a new sample each frame) denoised into sunMask_.
    std::unique_ptr<shadows::ShadowDenoiser> shadowDenoiser_;
    float sunAngle_ = 0.0f;
    uint32_t softShadowFrames_ = 0;  // frames the denoiser has accumulated (0: its history starts over)
    // shadow_sun.glsl's read buffer: the cascades of this frame and the sun.
    struct ShadowData {
        glm::mat4 viewProjection[kShadowCascades];
        glm::vec4 splitFar, texelSize, depthRange, forward, irradiance, direction, bias;
    };
    rhi::ShaderHandle sunLight_;
    rhi::BufferHandle shadowData_;
    rhi::ShaderHandle shadowVertex_;
    rhi::ShaderHandle shadowAlphaFragment_;  // with shadowVertex_ = shadow_depth_alpha.vert: scenes with alpha-tested materials
    rhi::TextureHandle shadowMap_;
    std::array<ShadowCascade, kShadowCascades> cascades_{};
    glm::vec3 sunDirection_{0.0f, 1.0f, 0.0f}, sunIrradiance_{0.0f};
    glm::vec3 sceneMin_{0.0f}, sceneMax_{0.0f};
    std::unique_ptr<gbuffer::DepthPyramid> depthPyramid_;
    // raster_renderer_sdf.cpp: foliage's alpha pass
    bool alphaAwareFoliage() const;  // FoliageMode::AlphaAware in a scene with alpha-tested meshes
    bool createAlphaPass(std::string* error);
    void runAlphaPass();  // right after the frame's field update (updateDistanceField)
    rhi::ShaderHandle alphaPassVertex_, alphaPassFragment_;
    // raster_renderer_reflections.cpp
    bool createReflections(std::string* error);
    void destroyReflections();
    void traceReflections(bool resetHistory);  // after GI, before the composite
    std::unique_ptr<reflections::ReflectionClassifier> reflectionClassifier_;
    std::unique_ptr<reflections::ReflectionDenoiser> reflectionDenoiser_;
    rhi::TextureHandle specularAlbedo_;  // the split sum's (A, B) over n·v and roughness (specular_albedo.h)
    rhi::SamplerHandle linear_;
    rhi::TextureHandle reflections_, reflectionTraced_;  // reflections_ is a 1×1 transparent stand-in when off
    uint32_t reflectionFrame_ = 0;
    Image readGi(rhi::TextureHandle t);
    bool drawDebugView(View view, float exposure, Error* error);  // into debugView_
    rhi::IDevice& device_;
    RasterOptions options_;
    std::unique_ptr<GpuScene> scene_;
    rhi::ShaderHandle vertex_, fragment_, lighting_, composite_;
    rhi::TextureHandle albedo_, normal_, emission_, motion_, position_, depth_;
    rhi::TextureHandle lit_, giDiffuse_, giSpecular_;
    rhi::TextureHandle giSky_;  // 1×1 equirectangular: the sky as GI's environment (DispatchDesc::environmentInDirectLight)
    glm::vec3 giSkyUploaded_{-1.0f};
    rhi::SamplerHandle point_;
    rhi::ShaderHandle display_;      // render/display.comp, created at the first drawView
    rhi::TextureHandle debugView_;   // RGBA8 scratch for the SDF and GI debug views, likewise
    rhi::BufferHandle direct_, combined_;  // direct_: this frame's estimate (the sun's passes add to it)
    rhi::ShaderHandle accumulateDirect_;
    rhi::BufferHandle directMean_;  // the direct light over frames: what the composite and the AOV read
    rhi::BufferHandle directHistory_[2], directPoints_[2];  // ping-pong: rgb + frames; surface point + normal
    uint32_t directParity_ = 0;
    bool directHistoryValid_ = false;
    bool sceneMoved_ = false;  // setScene since the last frame
    SceneLightConstants previousLight_{};
    glm::vec3 previousEye_{0.0f};
    std::unique_ptr<sdf::SdfScene> sdf_;
    std::vector<sdf::InstanceHandle> sdfInstances_;
    std::vector<glm::mat4> sdfTransforms_;
    struct DeformingMesh {
        uint32_t mesh = 0;  // in the scene
        rhi::BufferHandle positions, indices;
    };
    std::vector<DeformingMesh> sdfDeforming_;
    glm::vec3 sdfCenter_{0.0f}, sceneCenter_{0.0f};
    std::unique_ptr<gi::GiContext> gi_;
    std::unique_ptr<vct::Clipmap> clipmap_;
    std::unique_ptr<vct::ConeTracer> coneTracer_;
    rhi::ShaderHandle vctVertex_, vctEmittance_;
    glm::uvec2 probePixel_{~0u, ~0u};  // View::VctConeSamples' pixel (~0: the centre, set at creation)
    Image readDebugView();  // debugView_ as an image (0..1)
    GiLights giLights_;
    rhi::ShaderHandle glassFragment_;
    rhi::TextureHandle glassRadiance_, glassDepth_;  // 1×1 until a frame draws glass
    bool glassDrawn_ = false;
    bool cut_ = false;
    scenes::Camera camera_;
    glm::mat4 view_{1.0f}, projection_{1.0f}, previousView_{1.0f}, previousProjection_{1.0f};
    glm::mat4 viewProjection_{1.0f}, previousViewProjection_{1.0f};
    uint32_t frame_ = 0;
};

// The nearest surface wins: `depth` cleared to the far plane, tested and written with Less.
void depthTestAgainstCleared(rhi::DrawCallState& draw, rhi::TextureHandle depth);

// The renderer's camera matrices: right-handed view; projection with depth [0, 1] and clip-space y down
// (row 0 at the top).
glm::mat4 viewMatrix(const scenes::Camera& camera);
glm::mat4 projectionMatrix(const scenes::Camera& camera, float aspect, float sceneSize);
glm::mat4 viewProjection(const scenes::Camera& camera, float aspect, float sceneSize);

// A mesh's material as the distance field keeps it (sdf::InstanceDesc::material; raster_renderer_sdf.cpp).
sdf::SurfaceMaterial fieldMaterialOf(const scenes::TriangleMesh& mesh);

// (raster_renderer_gi.cpp)
GiLights giLightsOf(const scenes::SceneGeometry& scene);

}  // namespace bricklight::render
