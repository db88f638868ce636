#include "raster_renderer.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace bricklight::render {

namespace {
float halfToFloat(uint16_t h) {  // IEEE binary16 -> float (the G-buffer's RGBA16F/RG16F targets)
    const uint32_t e = (h >> 10) & 0x1Fu, m = h & 0x3FFu;
    float f = e == 0 ? std::ldexp(float(m), -24) : e == 31 ? (m ? NAN : INFINITY) : std::ldexp(float(m | 0x400u), int(e) - 25);
    return (h & 0x8000u) ? -f : f;
}
}

glm::mat4 viewProjection(const scenes::Camera& camera, float aspect, float sceneSize) {
    const float distance = glm::length(camera.at - camera.eye);
    const float farPlane = 4.0f * (sceneSize + distance);
    const float nearPlane = farPlane * 1e-5f;
    glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(camera.verticalFovDegrees), aspect, nearPlane, farPlane);
    projection[1][1] = -projection[1][1];  // clip-space y down: the contract's image origin is top-left
    return projection * glm::lookAtRH(camera.eye, camera.at, camera.up);
}

std::unique_ptr<RasterRenderer> RasterRenderer::create(rhi::IDevice& device, const scenes::SceneGeometry& scene,
                                                       const RasterOptions& options, std::string* error) {
    auto fail = [&](const std::string& m) {
        if (error) *error = "raster renderer: " + m;
        return std::unique_ptr<RasterRenderer>();
    };
    std::string sceneError;
    if (!checkImageSize(options.width, options.height, &sceneError)) return fail(sceneError);
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
    rhi::SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = rhi::Filter::Nearest;
    sd.debugName = "gbuffer point";
    r->point_ = device.createSampler(sd);
    rhi::BufferDesc bd;
    bd.size = uint64_t(options.width) * options.height * 16;
    bd.debugName = "direct lighting";
    r->direct_ = device.createBuffer(bd);
    if (!r->vertex_ || !r->fragment_ || !r->lighting_ || !r->albedo_ || !r->normal_ || !r->emission_ || !r->motion_ || !r->position_ ||
        !r->depth_ || !r->point_ || !r->direct_)
        return fail("the device could not create the G-buffer or the lighting pass (see its messages)");
    if (!r->setCamera(scene.camera, error)) return nullptr;
    r->previousViewProjection_ = r->viewProjection_;
    return r;
}

RasterRenderer::~RasterRenderer() {
    for (rhi::TextureHandle t : {albedo_, normal_, emission_, motion_, position_, depth_})
        if (t) device_.destroy(t);
    for (rhi::ShaderHandle s : {vertex_, fragment_, lighting_})
        if (s) device_.destroy(s);
    if (point_) device_.destroy(point_);
    if (direct_) device_.destroy(direct_);
}

bool RasterRenderer::setCamera(const scenes::Camera& camera, std::string* error) {
    std::string why;
    if (!checkCamera(camera, &why)) {
        if (error) *error = "raster renderer: " + why;
        return false;
    }
    camera_ = camera;
    previousViewProjection_ = viewProjection_;
    viewProjection_ = viewProjection(camera, float(options_.width) / float(options_.height), scene_->rayOffset() * 1e5f);
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
    d.vertexInputs.push({0, rhi::VertexFormat::Float3, 0, 0});
    d.vertexInputs.push({1, rhi::VertexFormat::Float3, 0, 12});
    d.vertexInputs.push({2, rhi::VertexFormat::UInt1, 0, 24});
    d.vertexInputs.push({3, rhi::VertexFormat::Float3, 0, 28});
    d.vertexInputs.push({4, rhi::VertexFormat::Float2, 0, 40});
    d.vertexInputs.push({5, rhi::VertexFormat::Float3, 0, 48});
    d.vertexBuffers.push({scene_->vertexBuffer(), 0, GpuScene::kVertexStride, false});
    for (rhi::TextureHandle t : {albedo_, normal_, emission_, motion_, position_}) {
        rhi::ColorTarget c;
        c.view = rhi::wholeTexture(t);
        c.load = rhi::LoadOp::Clear;
        d.colorTargets.push(c);
    }
    d.depthTarget.view = rhi::wholeTexture(depth_);
    d.depthTarget.load = rhi::LoadOp::Clear;
    d.depthTarget.clearDepth = 1.0f;
    d.depth.testEnable = true;
    d.depth.writeEnable = true;
    d.depth.compare = rhi::CompareOp::Less;
    d.bindings.constants.push(rhi::constants(0, cam));
    d.bindings.readBuffers.push({2, scene_->materialBuffer(), {}});
    d.bindings.textures.push({0, rhi::wholeTexture(scene_->textureArray()), scene_->textureSampler()});
    rhi::DrawArgs args;
    args.vertexCount = 3 * scene_->triangleCount();
    device_.draw(d, args);

    struct {
        glm::mat4 inverseViewProjection;
        glm::vec4 eye;
        uint32_t size[4];
    } p{glm::inverse(viewProjection_), glm::vec4(camera_.eye, 1.0f), {options_.width, options_.height, options_.lightSamples, frame_++}};
    const SceneLightConstants light = scene_->lightConstants(options_.seed, 1);
    rhi::DispatchState s;
    s.shader = lighting_;
    s.label = "direct lighting";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.constants.push(rhi::constants(1, light));
    scene_->bind(s.bindings);
    uint8_t slot = 0;
    for (rhi::TextureHandle t : {albedo_, normal_, emission_, position_}) s.bindings.textures.push({slot++, rhi::wholeTexture(t), point_});
    s.bindings.storageBuffers.push({0, direct_, {}, rhi::Access::Write});
    device_.dispatch(s, (options_.width + 7) / 8, (options_.height + 7) / 8, 1);
}

bool RasterRenderer::setScene(const scenes::SceneGeometry& scene, std::string* error) {
    std::string sceneError;
    std::unique_ptr<GpuScene> next = GpuScene::create(device_, scene, &sceneError, &scene_->worldPositions());
    if (!next) {
        if (error) *error = "raster renderer: " + sceneError;
        return false;
    }
    scene_ = std::move(next);
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
        device_.readBuffer(direct_, 0, pixels * 16, v.data());
        for (size_t i = 0; i < pixels; ++i)
            for (int c = 0; c < 3; ++c) img.rgb[3 * i + size_t(c)] = v[i][c];
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
