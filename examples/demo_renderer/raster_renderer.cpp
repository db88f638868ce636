#include "raster_renderer.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "bricklight/half.h"
#include "specular_albedo.h"

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
    sd = rhi::SamplerDesc{};
    sd.mipFilter = rhi::Filter::Nearest;
    sd.debugName = "composite linear";
    r->linear_ = device.createSampler(sd);
    rhi::TextureDesc ad;
    ad.format = rhi::Format::RG32_FLOAT;
    ad.width = ad.height = kSpecularAlbedoSize;
    ad.usage = rhi::TextureUsage::Sampled;
    ad.debugName = "specular albedo";
    r->specularAlbedo_ = device.createTexture(ad);
    if (r->specularAlbedo_ && !device.writeTexture(r->specularAlbedo_, {}, specularAlbedoTable().data()))
        return fail("the device could not upload the specular albedo table (see its messages)");
    rhi::BufferDesc bd;
    bd.size = uint64_t(options.width) * options.height * 16;
    bd.debugName = "direct lighting";
    r->direct_ = device.createBuffer(bd);
    bd.debugName = "combined";
    r->combined_ = device.createBuffer(bd);
    if (!r->vertex_ || !r->fragment_ || !r->lighting_ || !r->composite_ || !r->albedo_ || !r->normal_ || !r->emission_ || !r->motion_ ||
        !r->position_ || !r->depth_ || !r->lit_ || !r->giDiffuse_ || !r->giSpecular_ || !r->point_ || !r->direct_ || !r->combined_ ||
        !r->linear_ || !r->specularAlbedo_)
        return fail("the device could not create the G-buffer or the lighting pass (see its messages)");
    rhi::ClearValue zero{};
    for (rhi::TextureHandle t : {r->lit_, r->giDiffuse_, r->giSpecular_}) device.clearTexture(t, 0, 1, zero);
    if (!r->createDirectHistory(error)) return nullptr;
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
    destroyDirectHistory();
    gi_.reset();
    sdf_.reset();
    for (const DeformingMesh& d : sdfDeforming_)
        for (rhi::BufferHandle b : {d.positions, d.indices})
            if (b) device_.destroy(b);
    coneTracer_.reset();
    clipmap_.reset();
    for (rhi::ShaderHandle s : {vctVertex_, vctEmittance_, glassFragment_, alphaPassVertex_, alphaPassFragment_})
        if (s) device_.destroy(s);
    for (rhi::TextureHandle t : {albedo_, normal_, emission_, motion_, position_, depth_, lit_, giDiffuse_, giSpecular_, giSky_, debugView_,
                                 glassRadiance_, glassDepth_, specularAlbedo_})
        if (t) device_.destroy(t);
    for (rhi::ShaderHandle s : {vertex_, fragment_, lighting_, composite_, display_})
        if (s) device_.destroy(s);
    if (point_) device_.destroy(point_);
    if (linear_) device_.destroy(linear_);
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
    view_ = viewMatrix(camera);
    projection_ = projectionMatrix(camera, float(options_.width) / float(options_.height), scene_->rayOffset() * 1e5f);
    viewProjection_ = projection_ * view_;
    return true;
}

// One frame, top to bottom: every pass in the order it is recorded. A pass whose technique is off records nothing
// (RasterOptions says which are on); each technique's wiring lives in its own file.
void RasterRenderer::render() {
    const bool cut = cut_;  // a camera cut: every history restarts this frame
    cut_ = false;
    drawGBuffer();                                       // this file
    buildDepthPyramid();                                 // this file (hybrid shadows' and reflections' screen-space steps)
    renderShadowMaps();                                  // raster_renderer_shadows.cpp
    updateDistanceField();                               // raster_renderer_sdf.cpp: the field, then the GI's alpha pass
    const SceneLightConstants light = lightDirect();     // this file: emitters, sky and (without maps) the sun
    classifyShadows();                                   // raster_renderer_shadows.cpp (hybrid)
    lightSunFromShadowMaps(light);                       // raster_renderer_shadows.cpp (maps and hybrid)
    accumulateDirectLight(light, cut);                   // raster_renderer_direct_history.cpp
    voxelizeVct();                                       // raster_renderer_vct.cpp
    dispatchGi(cut);                                     // raster_renderer_gi.cpp
    traceReflections(cut);                               // raster_renderer_reflections.cpp
    traceVct(cut);                                       // raster_renderer_vct.cpp
    renderGlass();                                       // raster_renderer_glass.cpp
    composite();                                         // this file
    shiftCameraHistory();                                // this file
}

// The G-buffer: albedo and roughness, normal, emission, motion and world position, depth.
void RasterRenderer::drawGBuffer() {
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
}

void RasterRenderer::buildDepthPyramid() {
    if (!depthPyramid_) return;
    Error why;
    if (!depthPyramid_->build(depth_, &why) && options_.errorCallback) options_.errorCallback(rhi::Severity::Error, why.message);
}

// Direct light through the BVH; returns the frame's light constants with the sun, for the shadow-map sun pass.
SceneLightConstants RasterRenderer::lightDirect() {
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
    return withSun;
}

// Direct + GI (+ glass, reflections) into the combined image, and the lit image the next frame's GI feeds back.
void RasterRenderer::composite() {
    struct {
        glm::vec4 eye;
        uint32_t size[4];
    } c{glm::vec4(camera_.eye, 1.0f), {options_.width, options_.height, giOn() ? 1u : 0u, options_.giFeedback ? 1u : 0u}};
    rhi::DispatchState k;
    k.shader = composite_;
    k.label = "composite";
    k.bindings.constants.push(rhi::constants(0, c));
    uint8_t slot = 0;
    for (rhi::TextureHandle t : {albedo_, normal_, emission_, position_, giDiffuse_, giSpecular_, glassRadiance_, reflections_})
        k.bindings.textures.push({slot++, rhi::wholeTexture(t), point_});
    k.bindings.textures.push({slot++, rhi::wholeTexture(specularAlbedo_), linear_});
    k.bindings.readBuffers.push({0, directMean_, {}});
    k.bindings.storageBuffers.push({0, combined_, {}, rhi::Access::Write});
    rhi::StorageImageBinding li;
    li.slot = 0;
    li.view = rhi::textureMip(lit_, 0);
    li.access = rhi::Access::Write;
    k.bindings.storageImages.push(li);
    device_.beginMarker("composite");
    device_.dispatch(k, (options_.width + 7) / 8, (options_.height + 7) / 8, 1);
    device_.endMarker();
}

gbuffer::Camera RasterRenderer::frameCamera() const {
    gbuffer::Camera c;
    c.view = view_;
    c.projection = projection_;
    c.previousView = previousView_;
    c.previousProjection = previousProjection_;
    return c;
}

gbuffer::Inputs RasterRenderer::frameGBuffer() const {
    gbuffer::Inputs g;
    g.depth = depth_;
    g.normals = normal_;
    g.normalsUnpackScale = glm::vec3(1.0f);  // float normals
    g.normalsUnpackOffset = glm::vec3(0.0f);
    g.roughness = albedo_;
    g.roughnessChannel = 3;
    g.motionVectors = motion_;
    return g;
}

// The next frame's motion vectors and GI reprojection start from this camera.
void RasterRenderer::shiftCameraHistory() {
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
    sceneMoved_ = true;
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
        device_.readBuffer(aov == Aov::Combined ? combined_ : directMean_, 0, pixels * 16, v.data());
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
