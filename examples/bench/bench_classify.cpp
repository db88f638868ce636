// bricklight-bench classify: the shadow classifier and hybrid shadows (include/bricklight/shadows/classifier.h) at the
// benchmark's resolution — the G-buffer and one sun shadow map traced through the scene's distance field
// (examples/bench/shaders/sdf_gbuffer.comp, sun_shadow_map.comp), then per frame: classify, the listed tiles' rays through
// the field, the resolve — with per-pass GPU times and the fraction of pixels that needed a ray; then soft shadows (a sun
// of 0.5°, one ray a pixel to a point of its disc, a new point each frame) and the shadow denoiser in place of the resolve.
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include "bench_common.h"
#include "bricklight/shadows/classifier.h"
#include "bricklight/shadows/denoiser.h"

namespace bricklight::bench {

int runClassify(const Options& o) {
    scenes::SceneGeometry geometry;
    std::unique_ptr<rhi::IDevice> device;
    if (!openBench(o, &geometry, &device)) return 1;
    const glm::vec3 lo = geometry.boundsMin, hi = geometry.boundsMax, extent = hi - lo;
    const float size = std::max(extent.x, std::max(extent.y, extent.z));
    auto scene = makeBenchScene(*device, geometry, o);
    if (!scene) return 1;
    for (int i = 0; i < 4; ++i) scene->update(geometry.camera.eye), device->endFrame();
    BenchGBuffer gbuffer;
    Error error;
    auto classifier = shadows::ShadowClassifier::create(*device, {o.width, o.height}, &error);
    rhi::TextureDesc td;
    td.format = rhi::Format::R16_FLOAT;
    td.width = o.width;
    td.height = o.height;
    td.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    td.debugName = "bench shadow mask";
    const rhi::TextureHandle mask = device->createTexture(td);
    const uint32_t mapSize = 2048;
    td.format = rhi::Format::R32_FLOAT;
    td.width = td.height = mapSize;
    td.debugName = "bench sun shadow map";
    const rhi::TextureHandle shadowMap = device->createTexture(td);
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("bench/sun_shadow_map.comp");
    const rhi::ShaderHandle mapShader = sd.blob ? device->createShader(sd) : rhi::ShaderHandle{};
    if (!classifier || !gbuffer.create(*device, o.width, o.height) || !mask || !shadowMap || !mapShader) {
        std::fprintf(stderr, "bricklight-bench: the device could not create the classifier's inputs%s%s\n", error.message.empty() ? "" : ": ", error.message.c_str());
        return 1;
    }
    // The sun of the benchmark's G-buffer (sdf_gbuffer.comp) and an orthographic map around the scene's bounding
    // sphere, looking along −sun.
    const glm::vec3 sun = glm::normalize(glm::vec3(-0.4f, 1.0f, 0.3f));
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float radius = 0.5f * glm::length(extent) * 1.01f;
    const glm::mat4 lightView = glm::lookAtRH(centre + sun * radius, centre, std::abs(sun.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
    // Light space → (u, v, depth): x, y over [−radius, radius], depth from the near plane over 2·radius.
    glm::mat4 toMap(1.0f);
    toMap[0][0] = toMap[1][1] = 0.5f / radius;
    toMap[2][2] = -0.5f / radius;
    toMap[3] = glm::vec4(0.5f, 0.5f, 0.0f, 1.0f);
    const glm::mat4 worldToShadow = toMap * lightView;
    const struct {
        glm::mat4 shadowToWorld;
        glm::vec4 direction;
        glm::uvec4 size;
    } mapParams{glm::inverse(worldToShadow), glm::vec4(-sun, 2.0f * radius), glm::uvec4(mapSize, mapSize, 0, 0)};
    rhi::DispatchState m;
    m.shader = mapShader;
    m.label = "bench sun shadow map";
    m.bindings.constants.push(rhi::constants(0, mapParams));
    m.bindings.storageImages.push(rhi::storageImage(0, shadowMap, rhi::Access::Write));
    scene->traceBindings(m.bindings);
    device->dispatch(m, mapSize / 8, mapSize / 8, 1);

    const float aspect = float(o.width) / float(o.height);
    const BenchCamera camera = cameraAt(geometry.camera, 0.0f, aspect, size);
    gbuffer.record(*device, *scene, camera, camera, o.width, o.height);
    shadows::ShadowClassifyDesc d;
    d.camera.view = camera.view;
    d.camera.projection = camera.projection;
    d.gbuffer.depth = gbuffer.depth;
    d.gbuffer.normals = gbuffer.normals;
    d.gbuffer.normalsUnpackScale = glm::vec3(1.0f);
    d.gbuffer.normalsUnpackOffset = glm::vec3(0.0f);
    d.sunDirection = sun;
    d.shadowMap = shadowMap;
    d.cascadeCount = 1;
    d.cascades[0] = {worldToShadow, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f), 2.0f * radius};
    d.blockerOffset = 2.0f / float(mapSize);
    d.blockerTaps = o.classifyTaps;
    d.rayNormalOffset = scene->desc().finestVoxelSize;
    shadows::ShadowClassifyCounts counts;
    auto frame = [&]() {
        device->beginMarker("shadow classify");
        bool ok = classifier->classify(d, &error);
        device->endMarker();
        device->beginMarker("shadow rays");
        ok = ok && classifier->trace(*scene, &error);
        device->endMarker();
        device->beginMarker("shadow resolve");
        ok = ok && classifier->resolve(mask, &error);
        device->endMarker();
        if (!ok) {
            std::fprintf(stderr, "bricklight-bench: %s\n", error.message.c_str());
            std::exit(1);
        }
        device->endFrame();
    };
    device->setTimingEnabled(false);
    for (int f = 0; f < 4; ++f) frame();  // warm-up
    device->waitIdle();
    device->setTimingEnabled(true);
    collect(*device, 0);
    for (uint32_t f = 0; f < o.frames; ++f) frame();
    const PhaseTimes t = collect(*device, o.frames);
    counts = classifier->readCounts();
    std::printf("scene %s: %s; %ux%u; one %u² sun map traced through the field, %u cascades of the field; %u blocker taps\n",
                geometry.name.c_str(), device->capabilities().deviceName.c_str(), o.width, o.height, mapSize, o.cascades, o.classifyTaps);
    std::printf("shadow classification %.3f ms, rays %.3f ms, resolve %.3f ms (mean of %u frames)\n", t.perFrame("shadow classify"),
                t.perFrame("shadow rays"), t.perFrame("shadow resolve"), o.frames);
    for (const auto& [label, ms] : t.total)  // the classifier's own markers inside the classification
        if (label.rfind("shadow classify/", 0) == 0) std::printf("  %-40s %9.3f ms\n", label.c_str(), ms / o.frames);
    const uint32_t pixels = o.width * o.height;
    std::printf("pixels facing the sun %u of %u; needing a ray %u (%.1f %% of all pixels) in %u listed tiles of %u\n", counts.activePixels, pixels,
                counts.rayPixels, 100.0 * counts.rayPixels / pixels, counts.listedTiles, classifier->tilesX() * classifier->tilesY());
    // What the blocker search decided without rays, against a ray for every sun-facing pixel (the normals mode, the
    // same rays): pixels whose answers differ are the search's wrong decisions (or the cascades mode's bounded ray
    // intervals).
    {
        auto readMask = [&]() {
            std::vector<uint16_t> halfs(size_t(o.width) * o.height);
            device->waitIdle();
            if (!device->readTexture(mask, {}, halfs.data())) halfs.clear();
            return halfs;
        };
        const std::vector<uint16_t> searched = readMask();
        d.mode = shadows::ShadowClassifyMode::Normals;
        frame();
        d.mode = shadows::ShadowClassifyMode::Cascades;
        const std::vector<uint16_t> traced = readMask();
        size_t differ = 0;
        for (size_t i = 0; i < searched.size() && i < traced.size(); ++i)
            differ += (glm::unpackHalf1x16(searched[i]) > 0.5f) != (glm::unpackHalf1x16(traced[i]) > 0.5f) ? 1 : 0;
        std::printf("decided against a ray for every sun-facing pixel: %zu pixels differ (%.3f %% of the sun-facing)\n", differ,
                    100.0 * double(differ) / std::max(1u, counts.activePixels));
    }
    // Soft shadows and the denoiser (a still camera: the history accumulates as in a still frame of a game).
    auto denoiser = shadows::ShadowDenoiser::create(*device, {o.width, o.height}, &error);
    if (!denoiser) {
        std::fprintf(stderr, "bricklight-bench: %s\n", error.message.c_str());
        return 1;
    }
    shadows::ShadowDenoiseDesc n;
    n.camera.view = n.camera.previousView = camera.view;
    n.camera.projection = n.camera.previousProjection = camera.projection;
    n.gbuffer.depth = gbuffer.depth;
    n.gbuffer.normals = gbuffer.normals;
    n.gbuffer.normalsUnpackScale = glm::vec3(1.0f);
    n.gbuffer.normalsUnpackOffset = glm::vec3(0.0f);
    n.output = mask;
    d.sunAngle = glm::radians(0.5f);
    d.softShadows = true;
    uint32_t softFrame = 0;
    auto softFrame_ = [&]() {
        d.frameIndex = softFrame;
        n.resetHistory = softFrame == 0;
        ++softFrame;
        device->beginMarker("shadow classify");
        bool ok = classifier->classify(d, &error);
        device->endMarker();
        device->beginMarker("soft shadow rays");
        ok = ok && classifier->trace(*scene, &error);
        device->endMarker();
        device->beginMarker("shadow denoise");
        ok = ok && denoiser->denoise(*classifier, n, &error);
        device->endMarker();
        if (!ok) {
            std::fprintf(stderr, "bricklight-bench: %s\n", error.message.c_str());
            std::exit(1);
        }
        device->endFrame();
    };
    device->setTimingEnabled(false);
    for (int f = 0; f < 4; ++f) softFrame_();
    device->waitIdle();
    device->setTimingEnabled(true);
    collect(*device, 0);
    for (uint32_t f = 0; f < o.frames; ++f) softFrame_();
    const PhaseTimes soft = collect(*device, o.frames);
    const shadows::ShadowClassifyCounts softCounts = classifier->readCounts();
    std::printf("soft shadows (sun 0.5 deg): classification %.3f ms, rays %.3f ms, denoise %.3f ms; soft trace + denoise %.3f ms (target 0.3 at "
                "1080p on the GPU); %u ray pixels in %u listed tiles\n",
                soft.perFrame("shadow classify"), soft.perFrame("soft shadow rays"), soft.perFrame("shadow denoise"),
                soft.perFrame("soft shadow rays") + soft.perFrame("shadow denoise"), softCounts.rayPixels, softCounts.listedTiles);
    denoiser.reset();
    device->destroy(mapShader);
    device->destroy(shadowMap);
    device->destroy(mask);
    gbuffer.destroy(*device);
    return 0;
}

}  // namespace bricklight::bench
