// Glass in the fast path: the example custom material of the cone-trace API (docs/vct.md, "Example custom
// material: glossy glass"). With a clip-map that holds light (--gi vxgi), meshes with transmission > 0 are not in
// the G-buffer nor in the voxelization (GpuScene puts them last in its vertex buffer, so both draws take the
// opaque range): the G-buffer, direct light and cone tracing see what lies behind the glass, and cones pass
// through it. After cone tracing, a forward draw of the glass range shades each glass pixel
// (examples/demo_renderer/shaders/glass.frag: rays through the glass's interfaces, cones from where they leave it) into a target
// of its own; the composite takes the glass pixels from there for the combined image.
//
// Why a target of its own rather than blending into the lit image: the combined image is a buffer the composite
// writes, and the lit image feeds GI the surfaces of the G-buffer (behind the glass), which must stay as they
// are. The glass pass tests its depth against the G-buffer's in the shader (the world position target: glass
// behind an opaque surface is discarded) and keeps the nearest glass surface with a depth target of its own, so
// the G-buffer's depth stays the opaque surfaces' for whoever reads it after the frame.
//
// Without a clip-map (--gi sdf, none, or voxel AO alone) there are no cones to trace: glass meshes are drawn as
// their opaque material (albedo, roughness, specular layer) in the G-buffer like any other mesh.
#include "raster_renderer.h"

namespace bricklight::render {

bool RasterRenderer::glassPassOn() const {
    return clipmap_ && options_.vctEmittance != vct::EmittanceMode::None && scene_->glassTriangleCount() > 0;
}

uint32_t RasterRenderer::rasterTriangleCount() const { return glassPassOn() ? scene_->opaqueTriangleCount() : scene_->triangleCount(); }

namespace {
rhi::TextureHandle glassTarget(rhi::IDevice& device, rhi::Format format, uint32_t width, uint32_t height, uint32_t usage, const char* name) {
    rhi::TextureDesc d;
    d.format = format;
    d.width = width;
    d.height = height;
    d.usage = usage | rhi::TextureUsage::Sampled;
    d.debugName = name;
    return device.createTexture(d);
}
}  // namespace

bool RasterRenderer::createGlass(std::string* error) {
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("render/glass.frag");
    glassFragment_ = sd.blob ? device_.createShader(sd) : rhi::ShaderHandle{};
    // Until glass is drawn the composite reads this single transparent texel (it clamps its reads to the size).
    glassRadiance_ = glassTarget(device_, rhi::Format::RGBA16_FLOAT, 1, 1, rhi::TextureUsage::RenderTarget, "glass radiance");
    if (!glassFragment_ || !glassRadiance_) {
        if (error) *error = "raster renderer: the device could not create the glass pass (see its messages)";
        return false;
    }
    device_.clearTexture(glassRadiance_, 0, 1, rhi::ClearValue{});
    return true;
}

void RasterRenderer::renderGlass() {
    if (!glassPassOn()) {
        // A scene without glass now (setScene): the composite must not take last frame's glass pixels.
        if (glassDrawn_) device_.clearTexture(glassRadiance_, 0, 1, rhi::ClearValue{});
        glassDrawn_ = false;
        return;
    }
    const rhi::TextureDesc* current = device_.describe(glassRadiance_);
    if (!glassDepth_ || !current || current->width != options_.width || current->height != options_.height) {
        device_.destroy(glassRadiance_);
        glassRadiance_ = glassTarget(device_, rhi::Format::RGBA16_FLOAT, options_.width, options_.height, rhi::TextureUsage::RenderTarget,
                                     "glass radiance");
        glassDepth_ = glassTarget(device_, rhi::Format::D32_FLOAT, options_.width, options_.height, rhi::TextureUsage::DepthTarget, "glass depth");
        if (!glassRadiance_ || !glassDepth_) return;  // the device reported why
    }
    struct {
        glm::mat4 viewProjection, previousViewProjection;
        glm::vec4 eye;
    } cam{viewProjection_, previousViewProjection_, glm::vec4(camera_.eye, 1.0f)};
    const glm::uvec4 glassParams(frame_, 0u, 0u, 0u);  // x frame (random numbers)
    const SceneLightConstants light = scene_->lightConstants(options_.seed, 1);  // the record points at these bytes
    rhi::DrawCallState d;
    d.label = "glass";
    d.vertexShader = vertex_;  // render/gbuffer.vert: the same vertices and outputs
    d.fragmentShader = glassFragment_;
    scene_->bindVertices(d);
    rhi::ColorTarget c;
    c.view = rhi::wholeTexture(glassRadiance_);
    c.load = rhi::LoadOp::Clear;  // alpha 0: no glass
    d.colorTargets.push(c);
    depthTestAgainstCleared(d, glassDepth_);
    d.bindings.constants.push(rhi::constants(0, cam));
    d.bindings.constants.push(rhi::constants(1, light));
    d.bindings.constants.push(rhi::constants(2, glassParams));
    scene_->bind(d.bindings);                // read buffers 0..6, base-colour textures (slot 4)
    clipmap_->traceBindings(d.bindings);     // textures 8 and 9, read buffer 7
    d.bindings.textures.push({0, rhi::wholeTexture(position_), point_});
    rhi::DrawArgs args;
    args.firstVertex = 3 * scene_->opaqueTriangleCount();
    args.vertexCount = 3 * scene_->glassTriangleCount();
    device_.beginMarker("glass");
    device_.draw(d, args);
    device_.endMarker();
    glassDrawn_ = true;
}

}  // namespace bricklight::render
