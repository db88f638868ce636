// bricklight-bench classify, second half: the reflection classifier and hybrid reflections
// (include/bricklight/reflections/classifier.h, reflection_denoiser.h, gi::GiContext::traceReflectionRays) at the
// benchmark's resolution, on the G-buffer traced through the scene's distance field (examples/bench/shaders/sdf_gbuffer.comp,
// roughness 0.4 everywhere: with the threshold at 0.5 every surface pixel is glossy, the worst case). Per frame: the
// depth pyramid, GI (for its radiance cache, not counted), the classification, the screen-space trace, the SDF rays,
// the denoiser — with per-pass GPU times and the fractions of pixels traced in screen space and through the field.
#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "bench_common.h"
#include "bricklight/gbuffer/depth_pyramid.h"
#include "bricklight/gi.h"
#include "bricklight/reflections/classifier.h"
#include "bricklight/reflections/denoiser.h"

namespace bricklight::bench {

int runReflections(const Options& o) {
    scenes::SceneGeometry geometry;
    std::unique_ptr<rhi::IDevice> device;
    if (!openBench(o, &geometry, &device)) return 1;
    const glm::vec3 extent = geometry.boundsMax - geometry.boundsMin;
    const float size = std::max(extent.x, std::max(extent.y, extent.z));
    auto scene = makeBenchScene(*device, geometry, o);
    if (!scene) return 1;
    const glm::vec3 centre = geometry.camera.eye;
    for (int i = 0; i < 4; ++i) scene->update(centre), device->endFrame();
    gi::ContextDesc cd;
    cd.displayWidth = o.width;
    cd.displayHeight = o.height;
    cd.internalResolution = gi::InternalResolution::Percent50;
    Error error;
    auto context = gi::GiContext::create(*device, *scene, cd, &error);
    auto pyramid = context ? gbuffer::DepthPyramid::create(*device, {o.width, o.height}, &error) : nullptr;
    auto classifier = pyramid ? reflections::ReflectionClassifier::create(*device, {o.width, o.height}, &error) : nullptr;
    auto denoiser = classifier ? reflections::ReflectionDenoiser::create(*device, {o.width, o.height}, &error) : nullptr;
    BenchGBuffer gbuffer;
    rhi::TextureDesc td;
    td.format = rhi::Format::RGBA16_FLOAT;
    td.width = o.width;
    td.height = o.height;
    td.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    td.debugName = "bench GI diffuse";
    const rhi::TextureHandle diffuse = device->createTexture(td);
    td.debugName = "bench GI specular";
    const rhi::TextureHandle specular = device->createTexture(td);
    td.debugName = "bench reflections traced";
    const rhi::TextureHandle traced = device->createTexture(td);
    td.debugName = "bench reflections";
    const rhi::TextureHandle reflections = device->createTexture(td);
    if (!denoiser || !gbuffer.create(*device, o.width, o.height) || !diffuse || !specular || !traced || !reflections) {
        std::fprintf(stderr, "bricklight-bench: the device could not create the reflections' inputs%s%s\n", error.message.empty() ? "" : ": ",
                     error.message.c_str());
        return 1;
    }
    const float aspect = float(o.width) / float(o.height);
    BenchCamera previous = cameraAt(geometry.camera, 0.0f, aspect, size);
    uint32_t samplesPerQuad = 4;
    auto frame = [&](uint32_t f) {
        const BenchCamera now = cameraAt(geometry.camera, 0.1f * float(f), aspect, size);
        scene->update(centre);
        gbuffer.record(*device, *scene, now, previous, o.width, o.height);
        gi::DispatchDesc g;
        g.camera.view = now.view;
        g.camera.projection = now.projection;
        g.camera.previousView = previous.view;
        g.camera.previousProjection = previous.projection;
        g.cameraPosition = now.eye;
        g.gbuffer.depth = gbuffer.depth;
        g.gbuffer.normals = g.gbuffer.roughness = gbuffer.normals;
        g.gbuffer.normalsUnpackScale = glm::vec3(1.0f);
        g.gbuffer.normalsUnpackOffset = glm::vec3(0.0f);
        g.gbuffer.roughnessChannel = 3;
        g.gbuffer.motionVectors = gbuffer.motion;
        g.previousLitOutput = gbuffer.lit;
        g.outputDiffuse = diffuse;
        g.outputSpecular = specular;
        if (!context->dispatch(g)) std::exit(1);
        Error why;
        device->beginMarker("reflections");
        device->beginMarker("depth pyramid");
        bool ok = pyramid->build(gbuffer.depth, &why);
        device->endMarker();
        reflections::ReflectionClassifyDesc c;
        c.camera.view = now.view;
        c.camera.projection = now.projection;
        c.camera.previousView = previous.view;
        c.camera.previousProjection = previous.projection;
        c.gbuffer.depth = gbuffer.depth;
        c.gbuffer.normals = c.gbuffer.roughness = gbuffer.normals;
        c.gbuffer.normalsUnpackScale = glm::vec3(1.0f);
        c.gbuffer.normalsUnpackOffset = glm::vec3(0.0f);
        c.gbuffer.roughnessChannel = 3;
        c.gbuffer.motionVectors = gbuffer.motion;
        c.roughnessThreshold = c.sdfRoughnessThreshold = 0.5f;
        c.frameIndex = f;
        c.samplesPerQuad = samplesPerQuad;
        device->beginMarker("classify");
        ok = ok && classifier->classify(c, &why);
        device->endMarker();
        reflections::ReflectionTraceDesc t;
        t.depthPyramid = pyramid->texture();
        t.previousLit = gbuffer.lit;
        t.output = traced;
        device->beginMarker("screen-space trace");
        ok = ok && classifier->traceScreenSpace(t, &why);
        device->endMarker();
        gi::ReflectionRaysDesc r;
        r.rays = classifier->sdfRayList();
        r.arguments = r.count = classifier->rayCounts();
        r.argumentsOffset = reflections::kReflectionArgsSdfTrace;
        r.countOffset = reflections::kReflectionCountSdfRays;
        r.frameIndex = f;
        r.output = traced;
        device->beginMarker("sdf rays");
        if (ok && !context->traceReflectionRays(r)) ok = false, why = context->lastError();
        device->endMarker();
        reflections::ReflectionDenoiseDesc d;
        d.tiles = classifier->denoiseTileList();
        d.arguments = d.count = classifier->rayCounts();
        d.argumentsOffset = reflections::kReflectionArgsDenoise;
        d.countOffset = reflections::kReflectionCountDenoiseTiles;
        d.radiance = traced;
        d.camera.view = now.view;
        d.camera.projection = now.projection;
        d.camera.previousView = previous.view;
        d.camera.previousProjection = previous.projection;
        d.gbuffer.depth = gbuffer.depth;
        d.gbuffer.normals = d.gbuffer.roughness = gbuffer.normals;
        d.gbuffer.normalsUnpackScale = glm::vec3(1.0f);
        d.gbuffer.normalsUnpackOffset = glm::vec3(0.0f);
        d.gbuffer.roughnessChannel = 3;
        d.output = reflections;
        device->beginMarker("denoise");
        ok = ok && denoiser->denoise(d, &why);
        device->endMarker();
        device->endMarker();
        if (!ok) {
            std::fprintf(stderr, "bricklight-bench: %s\n", why.message.c_str());
            std::exit(1);
        }
        device->endFrame();
        previous = now;
    };
    // All of a quad's pixels traced (the default), then one ray per 2×2 quad copied to the other three.
    for (uint32_t perQuad : {4u, 1u}) {
        samplesPerQuad = perQuad;
        device->setTimingEnabled(false);
        for (uint32_t f = 0; f < 16; ++f) frame(f);
        device->waitIdle();
        device->setTimingEnabled(true);
        collect(*device, 0);
        for (uint32_t f = 0; f < o.frames; ++f) frame(16 + f);
        const PhaseTimes times = collect(*device, o.frames);
        const reflections::ReflectionClassifyCounts n = classifier->readCounts();
        const double pixels = double(o.width) * o.height;
        std::printf("hybrid reflections, %s %ux%u, roughness 0.4 everywhere (threshold 0.5), %u ray(s) per 2x2 quad, %u frames:\n",
                    geometry.name.c_str(), o.width, o.height, perQuad, o.frames);
        std::printf("  %-22s %9.3f ms\n", "depth pyramid", times.perFrame("reflections/depth pyramid"));
        std::printf("  %-22s %9.3f ms\n", "classification", times.perFrame("reflections/classify"));
        std::printf("  %-22s %9.3f ms\n", "screen-space trace", times.perFrame("reflections/screen-space trace"));
        std::printf("  %-22s %9.3f ms\n", "SDF rays", times.perFrame("reflections/sdf rays"));
        std::printf("  %-22s %9.3f ms\n", "denoiser", times.perFrame("reflections/denoise"));
        std::printf("  %-22s %9.3f ms (GI %.3f ms and the G-buffer not included)\n", "hybrid reflections", times.perFrame("reflections"),
                    times.perFrame("gi"));
        for (const auto& [label, ms] : times.total)  // the passes' own markers inside the steps above
            if (label.rfind("reflections/", 0) == 0 && std::count(label.begin(), label.end(), '/') > 1)
                std::printf("    %-40s %9.3f ms\n", label.c_str() + 12, ms / o.frames);
        std::printf("  tiles: screen-space first %u, checkerboard %u, SDF only %u; denoised %u\n", n.screenSpaceFirstTiles,
                    n.checkerboardTiles, n.sdfOnlyTiles, n.denoiseTiles);
        std::printf("  pixels with a ray %.1f %% (screen-space %.1f %%: hits %.1f %%; SDF %.1f %%, the screen's misses included)\n",
                    100.0 * n.rayPixels / pixels, 100.0 * n.screenRays / pixels, 100.0 * n.screenHits / pixels, 100.0 * n.sdfRays / pixels);
    }
    for (rhi::TextureHandle h : {diffuse, specular, traced, reflections}) device->destroy(h);
    gbuffer.destroy(*device);
    return 0;
}

}  // namespace bricklight::bench
