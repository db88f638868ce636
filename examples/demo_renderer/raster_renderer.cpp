#include "raster_renderer.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "bricklight/half.h"

namespace bricklight::render {

void depthTestAgainstCleared(rhi::DrawCallState& d, rhi::TextureHandle depth) {
    d.depthTarget.view = rhi::wholeTexture(depth);
    d.depthTarget.load = rhi::LoadOp::Clear;
    d.depthTarget.clearDepth = 1.0f;
    d.depth.testEnable = true;
    d.depth.writeEnable = true;
    d.depth.compare = rhi::CompareOp::Less;
}

glm::mat4 viewMatrix(const scenes::Camera& camera) { return glm::lookAtRH(camera.eye, camera.at, camera.up); }

glm::mat4 projectionMatrix(const scenes::Camera& camera, float aspect, float sceneSize) {
    const float distance = glm::length(camera.at - camera.eye);
    const float farPlane = 4.0f * (sceneSize + distance);
    const float nearPlane = farPlane * 1e-5f;
    glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(camera.verticalFovDegrees), aspect, nearPlane, farPlane);
    projection[1][1] = -projection[1][1];  // clip-space y down: the contract's image origin is top-left
    return projection;
}

// The scene's sun and point/spot lights, for GI's relighting of what the camera does not see. (The sky is
// not among them: the renderer's direct lighting already holds it, so GI is given no environment.)
static std::vector<gi::Light> giLightsOf(const scenes::SceneGeometry& scene) {
    std::vector<gi::Light> lights;
    const scenes::Environment& env = scene.environment;
    if (env.sunIrradiance.x > 0.0f || env.sunIrradiance.y > 0.0f || env.sunIrradiance.z > 0.0f) {
        gi::Light sun;
        sun.type = gi::LightType::Directional;
        sun.direction = env.sunDirection;
        sun.color = env.sunIrradiance;
        lights.push_back(sun);
    }
    for (const scenes::PointLight& p : scene.pointLights) {
        if (lights.size() == gi::kMaxLights) break;
        gi::Light l;
        const bool spot = p.outerConeRadians <= 3.14159265f;
        l.type = spot ? gi::LightType::Spot : gi::LightType::Point;
        l.position = p.position;
        l.direction = p.direction;
        l.color = p.intensity;
        if (spot) {
            l.spotOuterAngle = p.outerConeRadians;
            l.spotInnerAngle = std::min(p.innerConeRadians, p.outerConeRadians);
        }
        lights.push_back(l);
    }
    return lights;
}

glm::mat4 viewProjection(const scenes::Camera& camera, float aspect, float sceneSize) {
    return projectionMatrix(camera, aspect, sceneSize) * viewMatrix(camera);
}

std::unique_ptr<RasterRenderer> RasterRenderer::create(rhi::IDevice& device, const scenes::SceneGeometry& scene,
                                                       const RasterOptions& options, std::string* error) {
    auto fail = [&](const std::string& m) {
        if (error) *error = "raster renderer: " + m;
        return std::unique_ptr<RasterRenderer>();
    };
    std::string sceneError;
    if (!checkImageSize(options.width, options.height, &sceneError)) return fail(sceneError);
    if (!checkStorageRange(device, uint64_t(options.width) * options.height * 16,
                           "the lighting buffers at " + std::to_string(options.width) + "x" + std::to_string(options.height), &sceneError))
        return fail(sceneError + ": render a smaller image");
    std::unique_ptr<GpuScene> gpuScene = GpuScene::create(device, scene, &sceneError);
    if (!gpuScene) return fail(sceneError);
    std::unique_ptr<RasterRenderer> r(new RasterRenderer(device));
    r->options_ = options;
    r->scene_ = std::move(gpuScene);
    auto shader = [&](const char* name) {
        rhi::ShaderDesc sd;
        sd.blob = rhi::findShader(name);
        return sd.blob ? device.createShader(sd) : rhi::ShaderHandle{};
    };
    r->vertex_ = shader("render/gbuffer.vert");
    r->fragment_ = shader("render/gbuffer.frag");
    r->lighting_ = shader("render/direct_light.comp");
    r->composite_ = shader("render/composite.comp");
    auto target = [&](rhi::Format format, const char* name, uint32_t usage) {
        rhi::TextureDesc d;
        d.format = format;
        d.width = options.width;
        d.height = options.height;
        d.usage = usage | rhi::TextureUsage::Sampled;
        d.debugName = std::string("gbuffer ") + name;
        return device.createTexture(d);
    };
    using namespace rhi::TextureUsage;
    r->albedo_ = target(rhi::Format::RGBA16_FLOAT, "albedo", RenderTarget);
    r->normal_ = target(rhi::Format::RGBA16_FLOAT, "normal", RenderTarget);
    r->emission_ = target(rhi::Format::RGBA16_FLOAT, "emission", RenderTarget);
    r->motion_ = target(rhi::Format::RG16_FLOAT, "motion", RenderTarget);
    r->position_ = target(rhi::Format::RGBA32_FLOAT, "position", RenderTarget);
    r->depth_ = target(rhi::Format::D32_FLOAT, "depth", DepthTarget);
    r->lit_ = target(rhi::Format::RGBA16_FLOAT, "lit", Storage);
    r->giDiffuse_ = target(rhi::Format::RGBA16_FLOAT, "diffuse GI", Storage);
    r->giSpecular_ = target(rhi::Format::RGBA16_FLOAT, "specular GI", Storage);
    rhi::SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = rhi::Filter::Nearest;
    sd.debugName = "gbuffer point";
    r->point_ = device.createSampler(sd);
    rhi::BufferDesc bd;
    bd.size = uint64_t(options.width) * options.height * 16;
    bd.debugName = "direct lighting";
    r->direct_ = device.createBuffer(bd);
    bd.debugName = "combined";
    r->combined_ = device.createBuffer(bd);
    if (!r->vertex_ || !r->fragment_ || !r->lighting_ || !r->composite_ || !r->albedo_ || !r->normal_ || !r->emission_ || !r->motion_ ||
        !r->position_ || !r->depth_ || !r->lit_ || !r->giDiffuse_ || !r->giSpecular_ || !r->point_ || !r->direct_ || !r->combined_)
        return fail("the device could not create the G-buffer or the lighting pass (see its messages)");
    rhi::ClearValue zero{};
    for (rhi::TextureHandle t : {r->lit_, r->giDiffuse_, r->giSpecular_}) device.clearTexture(t, 0, 1, zero);
    if (!r->createGlass(error)) return nullptr;
    if (!r->createShadows(scene, error)) return nullptr;
    const bool vct = options.gi && options.giTechnique == GiTechnique::Vct;
    if (options.gi && !vct && !r->createGi(scene, error)) return nullptr;
    r->giLights_ = giLightsOf(scene);
    r->sceneCenter_ = 0.5f * (scene.boundsMin + scene.boundsMax);
    if ((vct || options.vxao || (options.gi && options.giUnseenFromVct)) && !r->createVct(scene, error)) return nullptr;
    if (!r->createReflections(error)) return nullptr;
    if (!r->setCamera(scene.camera, error)) return nullptr;
    r->previousViewProjection_ = r->viewProjection_;
    r->previousView_ = r->view_;
    r->previousProjection_ = r->projection_;
    return r;
}

bool RasterRenderer::createSdf(const scenes::SceneGeometry& scene, std::string* error) {
    auto fail = [&](const std::string& m) {
        if (error) *error = "raster renderer: " + m;
        return false;
    };
    const glm::vec3 extent = scene.boundsMax - scene.boundsMin;
    const float side = std::max(extent.x, std::max(extent.y, extent.z));
    sdf::SceneDesc sd;
    sd.cascadeCount = options_.sdfCascades;
    // The finest cascade holds the whole scene with a margin; coarser ones catch rays that leave it.
    sd.finestVoxelSize = sdf::suggestVoxelSize(side * 1.1f, 1);
    // Hybrid shadows: finer cascades in front, centred on the camera (raster_renderer_shadows.cpp).
    const uint32_t finer = hybridShadowFinerCascades();
    sd.cascadeCount += finer;
    sd.finestVoxelSize /= float(1u << finer);
    sd.budgets = options_.sdfBudgets;
    sd.debugName = "render sdf";
    sd.errorCallback = options_.errorCallback;
    Error why;
    sdf_ = sdf::SdfScene::create(device_, sd, &why);
    if (!sdf_) return fail("the distance field for GI: " + why.message);
    std::vector<sdf::MeshHandle> meshes;
    for (const scenes::TriangleMesh& m : scene.meshes) {
        sdf::MeshArrays a;
        a.positions = m.positions.data();
        a.vertexCount = uint32_t(m.positions.size() / 3);
        a.indices = m.indices.data();
        a.indexCount = uint32_t(m.indices.size());
        a.name = m.name;
        meshes.push_back(sdf_->createMesh(a));
        if (!meshes.back()) return fail("the distance field rejected mesh '" + m.name + "': " + sdf_->lastError().message);
    }
    for (const scenes::MeshInstance& i : scene.instances) {
        const bool alphaTested = scene.meshes[i.mesh].alphaTested();
        sdfTransforms_.push_back(i.transform);
        if (alphaTested && options_.foliage == FoliageMode::LeftOut) {
            sdfInstances_.push_back({});  // not in the field (setScene skips it)
            continue;
        }
        sdf::InstanceDesc id;
        id.mesh = meshes[i.mesh];
        id.transform = i.transform;
        id.alphaTested = alphaTested && options_.foliage == FoliageMode::AlphaAware;
        sdfInstances_.push_back(sdf_->addInstance(id));
        if (!sdfInstances_.back()) return fail("the distance field rejected an instance: " + sdf_->lastError().message);
    }
    sdfCenter_ = sceneCenter_ = 0.5f * (scene.boundsMin + scene.boundsMax);
    return true;
}

bool RasterRenderer::createGi(const scenes::SceneGeometry& scene, std::string* error) {
    if (!sdf_ && !createSdf(scene, error)) return false;
    Error why;
    gi::ContextDesc gd;
    gd.displayWidth = options_.width;
    gd.displayHeight = options_.height;
    gd.internalResolution = options_.giResolution;
    gd.radianceCacheBricks = options_.giCacheBricks;
    gd.injectTile = options_.giInjectTile;
    gd.probeTile = options_.giProbeTile;
    gd.debugName = "render gi";
    gd.errorCallback = options_.errorCallback;
    if (alphaAwareFoliage()) gd.flags |= gi::ContextFlags::AlphaCache;
    // Cards left out of the field are in the G-buffer all the same: the camera self-check would count them.
    if (options_.foliage == FoliageMode::LeftOut && scene_->hasAlphaTested()) gd.flags |= gi::ContextFlags::NoCameraCheck;
    gi_ = gi::GiContext::create(device_, *sdf_, gd, &why);
    if (!gi_) {
        if (error) *error = "raster renderer: " + why.message;
        return false;
    }
    return !alphaAwareFoliage() || createAlphaPass(error);
}

void RasterRenderer::syncSdf(const scenes::SceneGeometry& scene) {
    if (!sdf_) return;
    for (size_t i = 0; i < scene.instances.size() && i < sdfInstances_.size(); ++i)
        if (sdfInstances_[i] && scene.instances[i].transform != sdfTransforms_[i]) {
            sdf_->setTransform(sdfInstances_[i], scene.instances[i].transform);
            sdfTransforms_[i] = scene.instances[i].transform;
        }
}

GBufferView RasterRenderer::gbuffer() const {
    GBufferView g;
    g.albedo = albedo_;
    g.normal = normal_;
    g.emission = emission_;
    g.motion = motion_;
    g.position = position_;
    g.depth = depth_;
    g.lit = lit_;
    g.view = view_;
    g.projection = projection_;
    g.previousView = previousView_;
    g.previousProjection = previousProjection_;
    g.eye = camera_.eye;
    return g;
}

RasterRenderer::~RasterRenderer() {
    destroyReflections();
    destroyShadows();
    gi_.reset();
    sdf_.reset();
    coneTracer_.reset();
    clipmap_.reset();
    for (rhi::ShaderHandle s : {vctVertex_, vctEmittance_, glassFragment_, alphaPassVertex_, alphaPassFragment_})
        if (s) device_.destroy(s);
    for (rhi::TextureHandle t : {albedo_, normal_, emission_, motion_, position_, depth_, lit_, giDiffuse_, giSpecular_, debugView_,
                                 glassRadiance_, glassDepth_})
        if (t) device_.destroy(t);
    for (rhi::ShaderHandle s : {vertex_, fragment_, lighting_, composite_, display_})
        if (s) device_.destroy(s);
    if (point_) device_.destroy(point_);
    if (direct_) device_.destroy(direct_);
    if (combined_) device_.destroy(combined_);
}

bool RasterRenderer::setCamera(const scenes::Camera& camera, std::string* error) {
    std::string why;
    if (!checkCamera(camera, &why)) {
        if (error) *error = "raster renderer: " + why;
        return false;
    }
    camera_ = camera;
    previousViewProjection_ = viewProjection_;
    previousView_ = view_;
    previousProjection_ = projection_;
    view_ = viewMatrix(camera);
    projection_ = projectionMatrix(camera, float(options_.width) / float(options_.height), scene_->rayOffset() * 1e5f);
    viewProjection_ = projection_ * view_;
    return true;
}

void RasterRenderer::render() {
    struct {
        glm::mat4 viewProjection, previousViewProjection;
        glm::vec4 eye;
    } cam{viewProjection_, previousViewProjection_, glm::vec4(camera_.eye, 1.0f)};
    rhi::DrawCallState d;
    d.label = "gbuffer";
    d.vertexShader = vertex_;
    d.fragmentShader = fragment_;
    scene_->bindVertices(d);
    for (rhi::TextureHandle t : {albedo_, normal_, emission_, motion_, position_}) {
        rhi::ColorTarget c;
        c.view = rhi::wholeTexture(t);
        c.load = rhi::LoadOp::Clear;
        d.colorTargets.push(c);
    }
    depthTestAgainstCleared(d, depth_);
    d.bindings.constants.push(rhi::constants(0, cam));
    d.bindings.readBuffers.push({2, scene_->materialBuffer(), {}});
    d.bindings.textures.push({0, rhi::wholeTexture(scene_->textureArray()), scene_->textureSampler()});
    rhi::DrawArgs args;
    args.vertexCount = 3 * rasterTriangleCount();  // without the glass range when the glass pass draws it
    // Markers name the passes in GPU timings (the viewer's table) and in captures.
    device_.beginMarker("gbuffer");
    device_.draw(d, args);
    device_.endMarker();
    if (depthPyramid_) {
        Error why;
        if (!depthPyramid_->build(depth_, &why) && options_.errorCallback) options_.errorCallback(rhi::Severity::Error, why.message);
    }
    renderShadowMaps();
    sdfUpdated_ = false;

    struct {
        glm::mat4 inverseViewProjection;
        glm::vec4 eye;
        uint32_t size[4];
    } p{glm::inverse(viewProjection_), glm::vec4(camera_.eye, 1.0f), {options_.width, options_.height, options_.lightSamples, frame_++}};
    SceneLightConstants light = scene_->lightConstants(options_.seed, 1);
    const SceneLightConstants withSun = light;
    // Shadow maps: the BVH path leaves the sun out; shadow_sun_light.comp adds it with the maps' visibility.
    if (mapsOn()) light.sunIrradiance = glm::vec4(0.0f);
    rhi::DispatchState s;
    s.shader = lighting_;
    s.label = "direct lighting";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.constants.push(rhi::constants(1, light));
    scene_->bind(s.bindings);
    uint8_t slot = 0;
    for (rhi::TextureHandle t : {albedo_, normal_, emission_, position_}) s.bindings.textures.push({slot++, rhi::wholeTexture(t), point_});
    s.bindings.storageBuffers.push({0, direct_, {}, rhi::Access::Write});
    device_.beginMarker("direct light");
    device_.dispatch(s, (options_.width + 7) / 8, (options_.height + 7) / 8, 1);
    device_.endMarker();
    classifyShadows();
    if (mapsOn()) lightSunFromShadowMaps(withSun);

    if (clipmap_) voxelizeVct();
    if (gi_) {
        if (!sdfUpdated_) {
            device_.beginMarker("sdf update");
            sdf_->update(sdfCenter_);
            device_.endMarker();
            runAlphaPass();
        }
        gi::DispatchDesc g;
        g.camera.view = view_;
        g.camera.projection = projection_;
        g.camera.previousView = previousView_;
        g.camera.previousProjection = previousProjection_;
        g.cameraPosition = camera_.eye;
        g.gbuffer.depth = depth_;
        g.gbuffer.normals = normal_;
        g.gbuffer.normalsUnpackScale = glm::vec3(1.0f);
        g.gbuffer.normalsUnpackOffset = glm::vec3(0.0f);
        g.gbuffer.roughness = albedo_;
        g.gbuffer.roughnessChannel = 3;
        g.gbuffer.motionVectors = motion_;
        g.previousLitOutput = lit_;
        if (options_.giRelight) {
            g.diffuseAlbedo = albedo_;  // base colour: metals' (small) diffuse part is overestimated off screen
            // The lit image fed back leaves emission out (direct lighting samples the emitters): re-lit
            // texels leave it out too, and their rays add it where they hit an emitter.
            g.emission = emission_;
            g.previousLitIncludesEmission = false;
            g.lights = giLights_.data();
            g.lightCount = uint32_t(giLights_.size());
        }
        g.outputDiffuse = giDiffuse_;
        g.outputSpecular = giSpecular_;
        g.trace = options_.giTrace;
        g.roughnessThreshold = options_.giRoughnessThreshold;
        g.resetHistory = cut_;
        g.unseenLight = options_.giUnseenFromVct ? clipmap_.get() : nullptr;
        const bool cut = cut_;
        cut_ = false;
        gi_->dispatch(g);
        traceReflections(cut);
    }
    traceVct();
    renderGlass();
    struct {
        glm::vec4 eye;
        uint32_t size[4];
    } c{glm::vec4(camera_.eye, 1.0f), {options_.width, options_.height, giOn() ? 1u : 0u, options_.giFeedback ? 1u : 0u}};
    rhi::DispatchState k;
    k.shader = composite_;
    k.label = "composite";
    k.bindings.constants.push(rhi::constants(0, c));
    slot = 0;
    for (rhi::TextureHandle t : {albedo_, normal_, emission_, position_, giDiffuse_, giSpecular_, glassRadiance_, reflections_})
        k.bindings.textures.push({slot++, rhi::wholeTexture(t), point_});
    k.bindings.readBuffers.push({0, direct_, {}});
    k.bindings.storageBuffers.push({0, combined_, {}, rhi::Access::Write});
    rhi::StorageImageBinding li;
    li.slot = 0;
    li.view = rhi::textureMip(lit_, 0);
    li.access = rhi::Access::Write;
    k.bindings.storageImages.push(li);
    device_.beginMarker("composite");
    device_.dispatch(k, (options_.width + 7) / 8, (options_.height + 7) / 8, 1);
    device_.endMarker();
    // The next frame's motion vectors and GI reprojection start from this camera.
    previousViewProjection_ = viewProjection_;
    previousView_ = view_;
    previousProjection_ = projection_;
}

bool RasterRenderer::setScene(const scenes::SceneGeometry& scene, std::string* error) {
    std::string sceneError;
    std::unique_ptr<GpuScene> next = GpuScene::create(device_, scene, &sceneError, &scene_->worldPositions());
    if (!next) {
        if (error) *error = "raster renderer: " + sceneError;
        return false;
    }
    next->continueCountOf(*scene_);
    scene_ = std::move(next);
    giLights_ = giLightsOf(scene);
    setSun(scene);
    syncSdf(scene);
    return true;
}

Image RasterRenderer::read(Aov aov) {
    Image img;
    img.width = options_.width;
    img.height = options_.height;
    const size_t pixels = size_t(img.width) * img.height;
    img.rgb.assign(pixels * 3, 0.0f);
    auto readTarget = [&](rhi::TextureHandle t, uint32_t channels, std::vector<uint16_t>& halves) {
        halves.resize(pixels * channels);
        device_.readTexture(t, {}, halves.data());
    };
    if (aov == Aov::Combined || aov == Aov::Direct) {
        std::vector<glm::vec4> v(pixels);
        device_.readBuffer(aov == Aov::Combined ? combined_ : direct_, 0, pixels * 16, v.data());
        for (size_t i = 0; i < pixels; ++i)
            for (int c = 0; c < 3; ++c) img.rgb[3 * i + size_t(c)] = v[i][c];
    } else if (aov == Aov::IndirectDiffuse) {
        return readGi(giDiffuse_);
    } else if (aov == Aov::Ao) {
        if (coneTracer_) return readAmbientOcclusion();  // zero without voxel cone tracing
    } else if (aov == Aov::Albedo || aov == Aov::Normal) {
        std::vector<uint16_t> h;
        readTarget(aov == Aov::Albedo ? albedo_ : normal_, 4, h);
        std::vector<float> depth(pixels);
        device_.readTexture(depth_, {}, depth.data());
        for (size_t i = 0; i < pixels; ++i)
            if (depth[i] < 1.0f)
                for (int c = 0; c < 3; ++c) img.rgb[3 * i + size_t(c)] = halfToFloat(h[4 * i + size_t(c)]);
    } else if (aov == Aov::Depth) {
        std::vector<glm::vec4> position(pixels);
        device_.readTexture(position_, {}, position.data());
        const glm::vec3 forward = glm::normalize(camera_.at - camera_.eye);
        for (size_t i = 0; i < pixels; ++i)
            if (position[i].w != 0.0f)
                img.rgb[3 * i] = img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = glm::dot(glm::vec3(position[i]) - camera_.eye, forward);
    }
    return img;
}

Image RasterRenderer::readGi(rhi::TextureHandle t) {
    Image img;
    img.width = options_.width;
    img.height = options_.height;
    const size_t pixels = size_t(img.width) * img.height;
    img.rgb.assign(pixels * 3, 0.0f);
    std::vector<uint16_t> h(pixels * 4);
    device_.readTexture(t, {}, h.data());
    for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) img.rgb[3 * i + size_t(c)] = halfToFloat(h[4 * i + size_t(c)]);
    return img;
}

Image RasterRenderer::readSpecularGi() { return readGi(giSpecular_); }

Image RasterRenderer::giDebugView(gi::DebugMode mode, float exposure) {
    Image img;
    if (!gi_) return img;
    rhi::TextureDesc d;
    d.format = rhi::Format::RGBA8_UNORM;
    d.width = options_.width;
    d.height = options_.height;
    d.usage = rhi::TextureUsage::Storage;
    d.debugName = "gi debug view";
    rhi::TextureHandle t = device_.createTexture(d);
    if (!t) return img;
    gi::DebugViewDesc desc;
    desc.mode = mode;
    desc.output = t;
    desc.exposure = exposure;
    if (gi_->debugView(desc)) {
        std::vector<uint8_t> bytes(size_t(d.width) * d.height * 4);
        device_.readTexture(t, {}, bytes.data());
        img.width = d.width;
        img.height = d.height;
        img.rgb.resize(size_t(d.width) * d.height * 3);
        for (size_t i = 0; i < img.rgb.size() / 3; ++i)
            for (int c = 0; c < 3; ++c) img.rgb[3 * i + size_t(c)] = float(bytes[4 * i + size_t(c)]) / 255.0f;
    }
    device_.destroy(t);
    return img;
}

Image RasterRenderer::readMotion() {
    Image img;
    img.width = options_.width;
    img.height = options_.height;
    const size_t pixels = size_t(img.width) * img.height;
    std::vector<uint16_t> h(pixels * 2);
    device_.readTexture(motion_, {}, h.data());
    img.rgb.assign(pixels * 3, 0.0f);
    for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 2; ++c) img.rgb[3 * i + size_t(c)] = halfToFloat(h[2 * i + size_t(c)]);
    return img;
}

}  // namespace bricklight::render
