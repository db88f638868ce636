// RasterRenderer::drawView: the renderer's images into a window's display texture (examples/demo_renderer/shaders/display.comp).
#include "raster_renderer.h"

namespace bricklight::render {

namespace {

// display.comp's mapping of a source, by what its texels hold.
enum DisplayMap : uint32_t { Radiance = 0, Color = 1, Signed = 2, Display = 3, Depth = 4, Motion = 5 };

}  // namespace

bool RasterRenderer::drawDebugView(View view, float exposure, Error* error) {
    if (!debugView_) {
        rhi::TextureDesc d;
        d.format = rhi::Format::RGBA8_UNORM;
        d.width = options_.width;
        d.height = options_.height;
        d.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
        d.debugName = "debug view";
        debugView_ = device_.createTexture(d);
        if (!debugView_) {
            *error = {ErrorCode::DeviceFailure, "the debug view's texture could not be created"};
            return false;
        }
    }
    bool drawn = false;
    if (view == View::VctConeSamples) {
        if (!coneTracer_) {
            *error = {ErrorCode::InvalidState, "needs the cone tracer (--gi vxgi or --ao vxao)"};
            return false;
        }
        return coneTracer_->debugConeSamples(std::min(probePixel_.x, options_.width - 1), std::min(probePixel_.y, options_.height - 1),
                                             debugView_, error);
    }
    if (view >= View::ReflectionTileClass) {
        return reflectionClassifier_->debugView(debugView_, reflections::ReflectionDebugMode(uint32_t(view) - uint32_t(View::ReflectionTileClass)),
                                                error);
    }
    if (viewIsVct(view)) {
        vct::DebugViewDesc desc;
        desc.mode = vct::DebugMode(uint32_t(view) - uint32_t(View::VctOpacity));
        desc.view = view_;
        desc.projection = projection_;
        desc.cameraPosition = camera_.eye;
        desc.output = debugView_;
        desc.exposure = exposure;
        if (!clipmap_->debugView(desc, error)) return false;
        drawn = true;
    } else if (view >= View::GiRadianceCache) {
        gi::DebugViewDesc desc;
        desc.mode = gi::DebugMode(uint32_t(view) - uint32_t(View::GiRadianceCache));
        desc.output = debugView_;
        desc.exposure = exposure;
        drawn = gi_->debugView(desc);
    } else {
        sdf::DebugViewDesc desc;
        desc.mode = sdf::DebugMode(uint32_t(view) - uint32_t(View::SdfDistance));
        desc.view = view_;
        desc.projection = projection_;
        desc.output = debugView_;
        drawn = sdf_->debugView(desc);
    }
    if (!drawn) *error = {ErrorCode::DeviceFailure, std::string("the debug view ") + viewName(view) + " failed (see the messages before)"};
    return drawn;
}

bool RasterRenderer::drawView(View view, rhi::TextureHandle display, const DisplayRect& rect, float exposure,
                              std::string* error) {
    Error why;
    auto fail = [&](const std::string& message) {
        if (error) *error = std::string("raster renderer: view ") + viewName(view) + ": " + message;
        return false;
    };
    if (view >= View::Count) return fail("not a view");
    if (viewIsVct(view) && !clipmap_) return fail("needs voxel cone tracing (--gi vxgi or --ao vxao)");
    if (viewNeedsGi(view) && !viewIsVct(view) && view >= View::SdfDistance && !gi_) return fail("needs the SDF GI (--gi sdf)");
    if (viewNeedsGi(view) && !giOn() && !gi_) return fail("needs GI, which is off");
    if (viewIsReflection(view) && !reflectionClassifier_) return fail("needs hybrid reflections (--reflections hybrid)");
    const rhi::TextureDesc* d = device_.describe(display);
    if (!d || d->format != rhi::Format::RGBA8_UNORM || !(d->usage & rhi::TextureUsage::Storage))
        return fail("the display texture must be a live RGBA8_UNORM texture with Storage usage");
    if (rect.width == 0 || rect.height == 0 || rect.x > d->width || rect.y > d->height || rect.width > d->width - rect.x ||
        rect.height > d->height - rect.y)
        return fail("the rectangle " + std::to_string(rect.width) + "x" + std::to_string(rect.height) + " at (" +
                    std::to_string(rect.x) + ", " + std::to_string(rect.y) + ") is empty or outside the display texture (" +
                    std::to_string(d->width) + "x" + std::to_string(d->height) + ")");
    if (!display_) {
        rhi::ShaderDesc sd;
        sd.blob = rhi::findShader("render/display.comp");
        display_ = sd.blob ? device_.createShader(sd) : rhi::ShaderHandle{};
        if (!display_) return fail("the shader render/display.comp could not be created");
    }
    // The source: the lighting buffers, a G-buffer or GI texture, or a debug view drawn now.
    rhi::TextureHandle texture = lit_;  // bound in every case: the shader declares both sources
    rhi::BufferHandle buffer = combined_;
    uint32_t map = Radiance, fromBuffer = 0;
    switch (view) {
        case View::Final: fromBuffer = 1; break;
        case View::Direct: buffer = directMean_, fromBuffer = 1; break;
        case View::IndirectDiffuse: texture = giDiffuse_; break;
        case View::SpecularGi: texture = giSpecular_; break;
        case View::Albedo: texture = albedo_, map = Color; break;
        case View::Normal: texture = normal_, map = Signed; break;
        case View::Depth: texture = position_, map = Depth; break;
        case View::Motion: texture = motion_, map = Motion; break;
        case View::Reflections: texture = reflections_; break;
        default:
            if (!drawDebugView(view, exposure, &why)) return fail(why.message);
            texture = debugView_, map = Display;
    }
    struct {
        uint32_t rect[4], source[4];
        float map[4];
    } c{{rect.x, rect.y, rect.width, rect.height},
        {options_.width, options_.height, map, fromBuffer},
        {exposure, camera_.eye.x, camera_.eye.y, camera_.eye.z}};
    rhi::DispatchState k;
    k.shader = display_;
    k.label = "display";
    k.bindings.constants.push(rhi::constants(0, c));
    k.bindings.textures.push({0, rhi::wholeTexture(texture), point_});
    k.bindings.readBuffers.push({0, buffer, {}});
    rhi::StorageImageBinding out;
    out.slot = 0;
    out.view = rhi::textureMip(display, 0);
    out.access = rhi::Access::Write;
    k.bindings.storageImages.push(out);
    device_.beginMarker("display");
    const bool ok = device_.dispatch(k, (rect.width + 7) / 8, (rect.height + 7) / 8, 1);
    device_.endMarker();
    return ok || fail("the display dispatch failed");
}

sdf::MemoryUse RasterRenderer::memoryUse() const {
    sdf::MemoryUse use;
    auto add = [&](const std::string& name, uint64_t bytes) {
        use.resources.push_back({name, bytes});
        use.totalBytes += bytes;
    };
    for (rhi::TextureHandle t : {albedo_, normal_, emission_, motion_, position_, depth_, lit_, giDiffuse_, giSpecular_, debugView_, glassRadiance_, glassDepth_}) {
        const rhi::TextureDesc* d = t ? device_.describe(t) : nullptr;
        if (d) add(d->debugName, rhi::subresourceBytes(*d, {}));
    }
    if (const rhi::TextureDesc* d = shadowMap_ ? device_.describe(shadowMap_) : nullptr) add(d->debugName, rhi::subresourceBytes(*d, {}));
    for (rhi::BufferHandle b : {direct_, directMean_, directHistory_[0], directHistory_[1], directPoints_[0], directPoints_[1], combined_, shadowData_}) {
        const rhi::BufferDesc* d = b ? device_.describe(b) : nullptr;
        if (d) add(d->debugName, d->size);
    }
    if (depthPyramid_) add("depth pyramid", depthPyramid_->memoryUse().totalBytes);
    return use;
}

}  // namespace bricklight::render
