// Hybrid reflections in the renderer (ReflectionMode::Hybrid, docs/render.md "Reflections"): after GI, the reflection
// classifier sorts the glossy pixels into screen-space and distance-field rays, the screen-space trace reads the
// previous frame's radiance through the depth pyramid, GI traces the rest (and the screen's misses) through the field
// into its radiance cache, and the denoiser filters the listed tiles; the composite takes the result over GI's
// specular by its weight.
#include "raster_renderer.h"

namespace bricklight::render {

namespace {

rhi::TextureHandle reflectionTexture(rhi::IDevice& device, uint32_t width, uint32_t height, const char* name) {
    rhi::TextureDesc td;
    td.format = rhi::Format::RGBA16_FLOAT;
    td.width = width;
    td.height = height;
    td.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::Storage;
    td.debugName = name;
    return device.createTexture(td);
}

}  // namespace

bool RasterRenderer::createReflections(std::string* error) {
    auto fail = [&](const std::string& why) {
        if (error) *error = "raster renderer: " + why;
        return false;
    };
    const bool hybrid = options_.reflections == ReflectionMode::Hybrid;
    if (hybrid && !gi_) return fail("hybrid reflections need the SDF GI (--gi sdf): their rays read its radiance cache");
    // Off: the composite reads one transparent texel.
    const uint32_t w = hybrid ? options_.width : 1, h = hybrid ? options_.height : 1;
    reflections_ = reflectionTexture(device_, w, h, "reflections");
    if (!reflections_) return fail("the device could not create the reflections' textures (see its messages)");
    device_.clearTexture(reflections_, 0, 1, rhi::ClearValue{});
    if (!hybrid) return true;
    Error why;
    reflectionTraced_ = reflectionTexture(device_, w, h, "reflections traced");
    if (!reflectionTraced_) return fail("the device could not create the reflections' textures (see its messages)");
    if (!depthPyramid_ && !(depthPyramid_ = gbuffer::DepthPyramid::create(device_, {w, h}, &why))) return fail(why.message);
    if (!(reflectionClassifier_ = reflections::ReflectionClassifier::create(device_, {w, h}, &why))) return fail(why.message);
    if (!(reflectionDenoiser_ = reflections::ReflectionDenoiser::create(device_, {w, h}, &why))) return fail(why.message);
    return true;
}

void RasterRenderer::destroyReflections() {
    reflectionClassifier_.reset();
    reflectionDenoiser_.reset();
    for (rhi::TextureHandle t : {reflections_, reflectionTraced_})
        if (t) device_.destroy(t);
}

void RasterRenderer::traceReflections(bool resetHistory) {
    if (!reflectionClassifier_ || !gi_) return;
    auto report = [&](const std::string& why) {
        if (options_.errorCallback) options_.errorCallback(rhi::Severity::Error, why);
    };
    Error why;
    reflections::ReflectionClassifyDesc c;
    c.camera = frameCamera();
    c.gbuffer = frameGBuffer();
    c.roughnessThreshold = options_.reflectionRoughness;
    c.sdfRoughnessThreshold = options_.reflectionRoughness;
    c.frameIndex = reflectionFrame_;
    device_.beginMarker("reflections");
    if (!reflectionClassifier_->classify(c, &why)) {
        device_.endMarker();
        return report(why.message);
    }
    reflections::ReflectionTraceDesc t;
    t.depthPyramid = depthPyramid_->texture();
    t.previousLit = lit_;  // the previous frame's (the composite rewrites it after this)
    t.output = reflectionTraced_;
    if (!reflectionClassifier_->traceScreenSpace(t, &why)) {
        device_.endMarker();
        return report(why.message);
    }
    gi::ReflectionRaysDesc r;
    r.rays = reflectionClassifier_->sdfRayList();
    r.arguments = r.count = reflectionClassifier_->rayCounts();
    r.argumentsOffset = reflections::kReflectionArgsSdfTrace;
    r.countOffset = reflections::kReflectionCountSdfRays;
    r.frameIndex = reflectionFrame_;
    r.output = reflectionTraced_;
    if (!gi_->traceReflectionRays(r)) {
        device_.endMarker();
        return report(gi_->lastError().message);
    }
    reflections::ReflectionDenoiseDesc d;
    d.tiles = reflectionClassifier_->denoiseTileList();
    d.arguments = d.count = reflectionClassifier_->rayCounts();
    d.argumentsOffset = reflections::kReflectionArgsDenoise;
    d.countOffset = reflections::kReflectionCountDenoiseTiles;
    d.radiance = reflectionTraced_;
    d.camera = frameCamera();
    d.gbuffer = frameGBuffer();
    d.resetHistory = resetHistory;
    d.output = reflections_;
    if (!reflectionDenoiser_->denoise(d, &why)) report(why.message);
    device_.endMarker();
    ++reflectionFrame_;
}

Image RasterRenderer::readReflections() { return reflectionClassifier_ ? readGi(reflections_) : Image{}; }

Image RasterRenderer::reflectionView(View view) {
    if (!reflectionClassifier_ || !viewIsReflection(view)) return {};
    if (view == View::Reflections) return readReflections();
    Error why;
    if (!drawDebugView(view, 1.0f, &why)) {
        if (options_.errorCallback) options_.errorCallback(rhi::Severity::Error, why.message);
        return {};
    }
    return readDebugView();
}

}  // namespace bricklight::render
