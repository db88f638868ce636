// The sun's cascaded shadow maps (RasterOptions::shadows = ShadowMode::ShadowMap): four depth-only draws of the
// scene through DrawCallState records, one per 2 × 2 tile of a D32_FLOAT atlas, fitted by shadow_cascades.cpp,
// then a pass that adds the sun with their visibility to the direct lighting (examples/demo_renderer/shaders/shadow_sun_light.comp,
// shadow_sun.glsl); and the optional depth pyramid of the G-buffer.
#include <algorithm>
#include <cmath>

#include "raster_renderer.h"

namespace bricklight::render {

namespace {

glm::vec3 towardsSun(const scenes::SceneGeometry& scene) {
    const glm::vec3 d = scene.environment.sunDirection;
    return glm::length(d) > 1e-6f ? glm::normalize(d) : glm::vec3(0.0f, 1.0f, 0.0f);
}

}  // namespace

void RasterRenderer::setSun(const scenes::SceneGeometry& scene) {
    sunDirection_ = towardsSun(scene);
    sunIrradiance_ = scene.environment.sunIrradiance;
    sunAngle_ = scene.environment.sunAngle;
    sceneMin_ = scene.boundsMin;
    sceneMax_ = scene.boundsMax;
}

bool checkSunShadowOptions(const SunShadowOptions& o, std::string* error) {
    auto fail = [&](const std::string& m) {
        if (error) *error = "sun shadows: " + m;
        return false;
    };
    auto inRange = [](float v, float lo, float hi) { return std::isfinite(v) && v >= lo && v <= hi; };
    if (o.resolution < kMinShadowResolution || o.resolution > kMaxShadowResolution)
        return fail("resolution " + std::to_string(o.resolution) + " is outside " + std::to_string(kMinShadowResolution) + ".." +
                    std::to_string(kMaxShadowResolution));
    if (!inRange(o.splitLambda, 0.0f, 1.0f)) return fail("splitLambda " + std::to_string(o.splitLambda) + " is outside 0..1");
    if (!inRange(o.shadowDistance, 0.0f, 1e30f)) return fail("shadowDistance must be 0 (automatic) or a positive finite distance");
    if (!inRange(o.slopeBias, 0.0f, 16.0f)) return fail("slopeBias " + std::to_string(o.slopeBias) + " is outside 0..16");
    if (!inRange(o.depthBias, 0.0f, 16.0f)) return fail("depthBias " + std::to_string(o.depthBias) + " is outside 0..16 texels");
    if (!inRange(o.normalOffset, 0.0f, 16.0f)) return fail("normalOffset " + std::to_string(o.normalOffset) + " is outside 0..16 texels");
    if (o.pcfRadius > kMaxShadowPcfRadius)
        return fail("pcfRadius " + std::to_string(o.pcfRadius) + " is outside 0.." + std::to_string(kMaxShadowPcfRadius));
    return true;
}

bool RasterRenderer::createShadows(const scenes::SceneGeometry& scene, std::string* error) {
    auto fail = [&](const std::string& m) {
        if (error) *error = "raster renderer: " + m;
        return false;
    };
    std::string invalid;
    if (!checkSunShadowOptions(options_.sunShadows, &invalid)) return fail(invalid);
    Error why;
    const bool maps = mapsOn();
    setSun(scene);
    if (maps) {
        const uint32_t r = options_.sunShadows.resolution;
        if (2 * r > device_.capabilities().limits.maxTextureSize2D)
            return fail("the shadow atlas (2 x 2 cascades of " + std::to_string(r) + "²) exceeds the device's 2D texture size");
        // Alpha-tested materials need a fragment shader that discards their cut-out texels; other scenes keep
        // the depth-only draw.
        const bool alpha = scene_->hasAlphaTested();
        for (auto [name, handle] : {std::pair{alpha ? "render/shadow_depth_alpha.vert" : "render/shadow_depth.vert", &shadowVertex_}, std::pair{options_.shadows == ShadowMode::Hybrid ? "render/shadow_sun_light_hybrid.comp" : "render/shadow_sun_light.comp", &sunLight_}}) {
            rhi::ShaderDesc sd;
            sd.blob = rhi::findShader(name);
            *handle = sd.blob ? device_.createShader(sd) : rhi::ShaderHandle{};
        }
        if (alpha) {
            rhi::ShaderDesc sd;
            sd.blob = rhi::findShader("render/shadow_alpha.frag");
            shadowAlphaFragment_ = sd.blob ? device_.createShader(sd) : rhi::ShaderHandle{};
            if (!shadowAlphaFragment_) return fail("the device could not create the alpha-tested shadow pass (see its messages)");
        }
        rhi::BufferDesc bd;
        bd.size = sizeof(ShadowData);
        bd.usage = rhi::BufferUsage::ShaderRead;
        bd.debugName = "sun shadow cascades";
        shadowData_ = device_.createBuffer(bd);
        rhi::TextureDesc td;
        td.format = rhi::Format::D32_FLOAT;
        td.width = td.height = 2 * options_.sunShadows.resolution;
        td.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::DepthTarget;
        td.debugName = "sun shadow cascades";
        shadowMap_ = device_.createTexture(td);
        if (!shadowVertex_ || !sunLight_ || !shadowData_ || !shadowMap_)
            return fail("the device could not create the sun's shadow maps or their passes (see its messages)");
    }
    if (options_.shadows == ShadowMode::Hybrid) {
        if (!sdf_ && !createSdf(scene, error)) return false;
        shadowClassifier_ = shadows::ShadowClassifier::create(device_, {options_.width, options_.height}, &why);
        if (!shadowClassifier_) return fail(why.message);
        rhi::TextureDesc md;
        md.format = rhi::Format::R16_FLOAT;
        md.width = options_.width;
        md.height = options_.height;
        md.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::Storage;
        md.debugName = "sun shadow mask";
        sunMask_ = device_.createTexture(md);
        if (!sunMask_) return fail("the device could not create the sun's shadow mask");
        if (sunAngle_ > 0.0f) {
            shadowDenoiser_ = shadows::ShadowDenoiser::create(device_, {options_.width, options_.height}, &why);
            if (!shadowDenoiser_) return fail(why.message);
            softShadowFrames_ = 0;
        }
    }
    if (options_.depthPyramid) {
        depthPyramid_ = gbuffer::DepthPyramid::create(device_, {options_.width, options_.height}, &why);
        if (!depthPyramid_) return fail(why.message);
    }
    return true;
}

void RasterRenderer::destroyShadows() {
    depthPyramid_.reset();
    shadowDenoiser_.reset();
    shadowClassifier_.reset();
    if (sunMask_) device_.destroy(sunMask_);
    sunMask_ = {};
    if (shadowMap_) device_.destroy(shadowMap_);
    for (rhi::ShaderHandle sh : {shadowVertex_, sunLight_, shadowAlphaFragment_})
        if (sh) device_.destroy(sh);
    if (shadowData_) device_.destroy(shadowData_);
    shadowMap_ = {};
    shadowVertex_ = sunLight_ = shadowAlphaFragment_ = {};
    shadowData_ = {};
}

void RasterRenderer::renderShadowMaps() {
    if (!mapsOn()) return;
    const SunShadowOptions& o = options_.sunShadows;
    CascadeFitDesc f;
    f.eye = camera_.eye;
    f.forward = glm::normalize(camera_.at - camera_.eye);
    f.verticalFovDegrees = camera_.verticalFovDegrees;
    f.aspect = float(options_.width) / float(options_.height);
    f.nearPlane = projection_[3][2] / projection_[2][2];  // perspectiveRH_ZO: zFar·zNear/(zNear − zFar) over zFar/(zNear − zFar)
    float reach = o.shadowDistance;
    if (reach <= 0.0f)  // automatic: the farthest corner of the scene's bounds along the view
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 p((c & 1) ? sceneMax_.x : sceneMin_.x, (c & 2) ? sceneMax_.y : sceneMin_.y, (c & 4) ? sceneMax_.z : sceneMin_.z);
            reach = std::max(reach, glm::dot(p - f.eye, f.forward));
        }
    f.shadowDistance = std::max(reach, 4.0f * f.nearPlane);
    f.splitLambda = o.splitLambda;
    f.resolution = o.resolution;
    f.sunDirection = sunDirection_;
    f.sceneMin = sceneMin_;
    f.sceneMax = sceneMax_;
    cascades_ = fitCascades(f);
    device_.beginMarker("sun shadow maps");
    for (uint32_t i = 0; i < kShadowCascades; ++i) {
        rhi::DrawCallState d;
        d.label = "sun shadow cascade";
        d.vertexShader = shadowVertex_;
        scene_->bindVertices(d);
        if (shadowAlphaFragment_) {
            // Position, material and texture coordinates (locations 0, 2, 4): what the alpha test reads.
            const auto all = d.vertexInputs;
            d.vertexInputs.count = 0;
            for (uint8_t k : {0, 2, 4}) d.vertexInputs.push(all.items[k]);
            d.fragmentShader = shadowAlphaFragment_;
            d.bindings.readBuffers.push({2, scene_->materialBuffer(), {}});
            d.bindings.textures.push({0, rhi::wholeTexture(scene_->textureArray()), scene_->textureSampler()});
        } else {
            d.vertexInputs.count = 1;  // location 0, the position: the only input the depth-only shader reads
        }
        d.depthTarget.view = rhi::textureMip(shadowMap_, 0);
        // The first draw clears the whole atlas; each draws into its tile through the viewport.
        d.depthTarget.load = i == 0 ? rhi::LoadOp::Clear : rhi::LoadOp::Load;
        const uint32_t r = o.resolution;
        d.viewport.x = float(shadowAtlasTile(i).x * r);
        d.viewport.y = float(shadowAtlasTile(i).y * r);
        d.viewport.width = d.viewport.height = float(r);
        d.depthTarget.clearDepth = 1.0f;
        d.depth.testEnable = true;
        d.depth.writeEnable = true;
        d.depth.compare = rhi::CompareOp::Less;
        d.raster.cull = rhi::CullMode::None;  // two-sided: the scenes hold single-sided sheets (cloth, planes)
        d.raster.depthBiasSlope = o.slopeBias;
        d.bindings.constants.push(rhi::constants(0, cascades_[i].viewProjection));
        rhi::DrawArgs args;
        args.vertexCount = 3 * scene_->triangleCount();  // every triangle casts, glass too (as the BVH's rays see it)
        device_.draw(d, args);
    }
    device_.endMarker();
}

void RasterRenderer::lightSunFromShadowMaps(const SceneLightConstants& light) {
    if (!mapsOn()) return;
    ShadowData k{};
    for (uint32_t i = 0; i < kShadowCascades; ++i) {
        k.viewProjection[i] = cascades_[i].viewProjection;
        k.splitFar[int(i)] = cascades_[i].splitFar;
        k.texelSize[int(i)] = cascades_[i].texelSize;
        k.depthRange[int(i)] = std::max(cascades_[i].depthRange, 1e-6f);
    }
    k.forward = glm::vec4(glm::normalize(camera_.at - camera_.eye), 0.0f);
    k.irradiance = glm::vec4(sunIrradiance_, 0.0f);
    k.direction = glm::vec4(sunDirection_, 0.0f);
    const SunShadowOptions& o = options_.sunShadows;
    k.bias = glm::vec4(o.normalOffset, o.depthBias, float(o.pcfRadius), float(o.resolution));
    device_.writeBuffer(shadowData_, 0, &k, sizeof(k));
    struct {
        glm::vec4 eye;
        uint32_t size[4];
    } p{glm::vec4(camera_.eye, 1.0f), {options_.width, options_.height, 0, 0}};
    rhi::DispatchState s;
    s.shader = sunLight_;
    s.label = "sun from shadow maps";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.constants.push(rhi::constants(1, light));
    scene_->bind(s.bindings);
    uint8_t slot = 0;
    for (rhi::TextureHandle t : {albedo_, normal_, emission_, position_}) s.bindings.textures.push({slot++, rhi::wholeTexture(t), point_});
    s.bindings.textures.push({5, rhi::wholeTexture(shadowMap_), point_});
    if (sunMask_) s.bindings.textures.push({6, rhi::wholeTexture(sunMask_), point_});
    s.bindings.readBuffers.push({7, shadowData_, {}});
    s.bindings.storageBuffers.push({0, direct_, {}, rhi::Access::ReadWrite});
    device_.beginMarker(sunMask_ ? "sun hybrid shadow light" : "sun shadow light");
    device_.dispatch(s, (options_.width + 7) / 8, (options_.height + 7) / 8, 1);
    device_.endMarker();
}

ShadowCascadesView RasterRenderer::shadowCascades() const {
    ShadowCascadesView v;
    if (!mapsOn()) return v;
    v.depth = shadowMap_;
    v.cascades = cascades_;
    v.resolution = options_.sunShadows.resolution;
    v.sunDirection = sunDirection_;
    return v;
}

Image RasterRenderer::readSunVisibility() {
    Image img;
    if (!mapsOn()) return img;
    img.width = options_.width;
    img.height = options_.height;
    const size_t pixels = size_t(img.width) * img.height;
    std::vector<glm::vec4> v(pixels);
    device_.readBuffer(direct_, 0, pixels * 16, v.data());
    img.rgb.resize(pixels * 3);
    for (size_t i = 0; i < pixels; ++i) img.rgb[3 * i] = img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = v[i].w;
    return img;
}

uint32_t RasterRenderer::hybridShadowFinerCascades() const {
    if (options_.shadows != ShadowMode::Hybrid) return 0;
    // Three finer cascades around the camera: the fewest after which the rays' answers stop improving (the
    // measurements: docs/notes/shadows-hybrid.md, "Finer cascades around the camera").
    return 3;
}

// Hybrid: the shadow classifier over the cascades as shadow_sun.glsl reads them (the atlas's tiles), rays through
// the distance field for the tiles it lists, and the shadow mask the sun pass reads (with a sun of angular size:
// soft rays and the shadow denoiser's visibility).
void RasterRenderer::classifyShadows() {
    if (options_.shadows != ShadowMode::Hybrid) return;
    shadows::ShadowClassifyDesc d;
    d.camera = frameCamera();
    d.gbuffer = frameGBuffer();
    d.sunDirection = sunDirection_;
    d.shadowMap = shadowMap_;
    d.cascadeCount = kShadowCascades;
    for (uint32_t i = 0; i < kShadowCascades; ++i) {
        // Cascade i's clip space onto its tile of the 2 × 2 atlas: uv = tile / 2 + (clip.xy / 2 + 1/2) / 2.
        const glm::vec2 tile(shadowAtlasTile(i));
        glm::mat4 toAtlas(1.0f);
        toAtlas[0][0] = toAtlas[1][1] = 0.25f;
        toAtlas[3] = glm::vec4(0.25f + 0.5f * tile.x, 0.25f + 0.5f * tile.y, 0.0f, 1.0f);
        d.cascades[i].worldToShadow = toAtlas * cascades_[i].viewProjection;
        d.cascades[i].uvRect = glm::vec4(0.5f * tile, 0.5f * tile + 0.5f);
        d.cascades[i].depthRange = std::max(cascades_[i].depthRange, 1e-6f);
    }
    // Two of the finest cascade's texels of depth: the maps' own precision, as their PCF bias takes it.
    d.blockerOffset = std::min(2.0f * cascades_[0].texelSize / d.cascades[0].depthRange, 0.5f);
    // Sure rays only: a ray decides where the field's answer is sure and the maps keep the rest (the field's voxels
    // are ~1 m in the atrium, the maps' texels millimetres). The rays start on the surface (half a texel of the
    // finest cascade off it) and leave their own receiver along the ray, not along the normal: an origin a voxel
    // out along the normal (the first version) moved the shadow edges the rays draw by up to a voxel sideways.
    d.sureRaysOnly = true;
    d.markUnsurePixels = true;  // shadow_sun_light_hybrid.comp takes its PCF answer there
    d.rayNormalOffset = 0.5f * cascades_[0].texelSize;
    // Foliage: the rays pass the cut-out parts of alpha-tested cards by the GI's alpha cache (its alpha pass has run
    // this frame); a GI context without the cache hands out a stand-in that says so, and without GI the cards are
    // solid to the rays. A hard sun keeps frameIndex 0: each pixel's draws stay put (a stable dither, no flicker).
    d.alphaCache = gi_ ? gi_->alphaCacheBuffer() : rhi::BufferHandle{};
    // A sun of angular size: one ray a pixel to a point of its disc, a new point each frame, denoised over frames and
    // neighbours; the blocker search then spans the sun's real size.
    const bool soft = shadowDenoiser_ != nullptr;
    if (soft) {
        // Soft rays are samples the denoiser averages: an unsure sample replaced by the taps' majority biases the
        // penumbra (atrium, 3 degrees, penumbra relMSE 0.82 with sure rays vs 0.63 without, at 2 finer cascades), so
        // every ray decides.
        d.sureRaysOnly = false;
        d.markUnsurePixels = false;
        d.sunAngle = sunAngle_;
        d.softShadows = true;
        d.frameIndex = softShadowFrames_;
    }
    Error why;
    device_.beginMarker("shadow classify");
    bool ok = shadowClassifier_->classify(d, &why);
    device_.endMarker();
    device_.beginMarker("shadow rays");
    ok = ok && shadowClassifier_->trace(*sdf_, &why);
    device_.endMarker();
    if (soft) {
        shadows::ShadowDenoiseDesc n;
        n.camera = frameCamera();
        n.gbuffer = frameGBuffer();
        n.output = sunMask_;
        n.resetHistory = softShadowFrames_ == 0;
        device_.beginMarker("shadow denoise");
        ok = ok && shadowDenoiser_->denoise(*shadowClassifier_, n, &why);
        device_.endMarker();
        softShadowFrames_ += ok ? 1u : 0u;
    } else {
        ok = ok && shadowClassifier_->resolve(sunMask_, &why);
    }
    if (!ok && options_.errorCallback) options_.errorCallback(rhi::Severity::Error, why.message);
}

}  // namespace bricklight::render
