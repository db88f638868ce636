#include "passes.h"

namespace integration {

using namespace bricklight;

std::unique_ptr<Passes> Passes::create(rhi::IDevice& device, uint32_t width, uint32_t height, std::string* error) {
    std::unique_ptr<Passes> p(new Passes(device));
    p->width_ = width;
    p->height_ = height;
    auto image = [&](rhi::Format format, uint32_t usage, const char* name) {
        rhi::TextureDesc d;
        d.format = format;
        d.width = width;
        d.height = height;
        d.usage = usage;
        d.debugName = name;
        return device.createTexture(d);
    };
    using namespace rhi::TextureUsage;
    FrameImages& i = p->images_;
    i.depth = image(rhi::Format::D32_FLOAT, DepthTarget | Sampled, "depth");
    i.normal = image(rhi::Format::RGBA16_FLOAT, RenderTarget | Sampled, "normal");
    i.albedo = image(rhi::Format::RGBA8_UNORM, RenderTarget | Sampled, "albedo + roughness");
    i.motion = image(rhi::Format::RG16_FLOAT, RenderTarget | Sampled, "motion");
    // GI writes its outputs as storage images; our composite samples them.
    i.giDiffuse = image(rhi::Format::RGBA16_FLOAT, Storage | Sampled, "GI diffuse");
    i.giSpecular = image(rhi::Format::RGBA16_FLOAT, Storage | Sampled, "GI specular");
    i.lit = image(rhi::Format::RGBA16_FLOAT, Storage | Sampled, "lit");
    i.direct = image(rhi::Format::RGBA16_FLOAT, Storage, "direct");
    rhi::SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = rhi::Filter::Nearest;
    sd.debugName = "point";
    p->point_ = device.createSampler(sd);
    // Our shaders are in this program (bricklight_add_shaders registered them): looked up by name.
    auto shader = [&](const char* name) {
        rhi::ShaderDesc d;
        d.blob = rhi::findShader(name);
        return d.blob ? device.createShader(d) : rhi::ShaderHandle{};
    };
    p->gbufferVertex_ = shader("integration/gbuffer.vert");
    p->gbufferFragment_ = shader("integration/gbuffer.frag");
    p->composite_ = shader("integration/composite.comp");
    if (!i.depth || !i.normal || !i.albedo || !i.motion || !i.giDiffuse || !i.giSpecular || !i.lit || !i.direct || !p->point_ ||
        !p->gbufferVertex_ || !p->gbufferFragment_ || !p->composite_) {
        *error = "could not create the G-buffer, the composite's images or our shaders (see the messages above)";
        return nullptr;
    }
    // Textures are undefined until written: the first frame's GI reads `lit` before any composite ran.
    device.clearTexture(i.lit, 0, 1, rhi::ClearValue{});
    return p;
}

Passes::~Passes() {
    for (rhi::TextureHandle t : {images_.depth, images_.normal, images_.albedo, images_.motion, images_.giDiffuse, images_.giSpecular,
                                 images_.lit, images_.direct})
        if (t) device_.destroy(t);
    for (rhi::ShaderHandle s : {gbufferVertex_, gbufferFragment_, composite_})
        if (s) device_.destroy(s);
    if (point_) device_.destroy(point_);
}

bool Passes::drawGBuffer(const RoomBuffers& room, const glm::mat4& viewProjection, const glm::mat4& previousViewProjection) {
    struct {
        glm::mat4 viewProjection, previousViewProjection;
    } camera{viewProjection, previousViewProjection};
    rhi::DrawCallState d;
    d.label = "application G-buffer";
    d.vertexShader = gbufferVertex_;
    d.fragmentShader = gbufferFragment_;
    // Buffer 0: the cube, per vertex (position, normal). Buffer 1: the boxes, per instance (3 transform rows, material).
    d.vertexBuffers.push({room.vertices, 0, 6 * sizeof(float), false});
    d.vertexBuffers.push({room.instances, 0, 4 * sizeof(glm::vec4), true});
    d.vertexInputs.push({0, rhi::VertexFormat::Float3, 0, 0});
    d.vertexInputs.push({1, rhi::VertexFormat::Float3, 0, 12});
    for (uint8_t row = 0; row < 4; ++row) d.vertexInputs.push({uint8_t(2 + row), rhi::VertexFormat::Float4, 1, 16u * row});
    d.indexBuffer = {room.indices, 0, rhi::IndexFormat::U32};
    for (rhi::TextureHandle t : {images_.normal, images_.albedo, images_.motion}) {
        rhi::ColorTarget c;
        c.view = rhi::wholeTexture(t);
        c.load = rhi::LoadOp::Clear;  // clear colour 0: normal (0,0,0) is "nothing here" for GI too
        d.colorTargets.push(c);
    }
    d.depthTarget.view = rhi::wholeTexture(images_.depth);
    d.depthTarget.load = rhi::LoadOp::Clear;
    d.depthTarget.clearDepth = 1.0f;
    d.depth.testEnable = true;
    d.depth.writeEnable = true;
    d.depth.compare = rhi::CompareOp::Less;
    d.raster.cull = rhi::CullMode::None;  // closed boxes: the depth test keeps the near side
    d.bindings.constants.push(rhi::constants(0, camera));
    rhi::DrawIndexedArgs args;
    args.indexCount = room.indexCount;
    args.instanceCount = room.instanceCount;
    return device_.drawIndexed(d, args);
}

bool Passes::composite(const sdf::SdfScene& field, const glm::mat4& viewProjection, const glm::vec3& eye, const Sun& sun,
                       float shadowRayOffset) {
    struct {
        glm::mat4 inverseViewProjection;
        glm::vec4 eye, sunDirection, sunIrradiance;
        uint32_t size[4];
    } params{glm::inverse(viewProjection), glm::vec4(eye, 1.0f), glm::vec4(sun.direction, shadowRayOffset),
             glm::vec4(sun.irradiance, 0.0f), {width_, height_, 0, 0}};
    rhi::DispatchState s;
    s.label = "application composite";
    s.shader = composite_;
    s.bindings.constants.push(rhi::constants(0, params));
    uint8_t slot = 0;
    for (rhi::TextureHandle t : {images_.depth, images_.normal, images_.albedo, images_.giDiffuse, images_.giSpecular})
        s.bindings.textures.push({slot++, rhi::wholeTexture(t), point_});
    s.bindings.storageImages.push({0, rhi::textureMip(images_.lit, 0), rhi::Access::Write});
    s.bindings.storageImages.push({1, rhi::textureMip(images_.direct, 0), rhi::Access::Write});
    // The distance field's atlas, cascade table, brick maps, trees and brick boxes, at the slots that
    // bricklight/trace.glsl declares (the defaults on both sides).
    field.traceBindings(s.bindings);
    return device_.dispatch(s, (width_ + 7) / 8, (height_ + 7) / 8, 1);
}

}  // namespace integration
