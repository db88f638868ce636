// bricklight-bench gi: GPU milliseconds per GI pass and GI's memory, on a G-buffer traced through the
// scene's distance field (examples/bench/shaders/sdf_gbuffer.comp; the G-buffer is timed apart from GI). The camera
// pans slowly so that reprojection and disocclusion do real work. In a scene with alpha-tested meshes (foliage)
// it runs twice, cards built opaque and alpha-aware (with the GI's alpha pass, drawn from the renderer's
// GpuScene with render/alpha_pass.vert and .frag), and prints what the alpha pass and the continued rays cost.
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <array>
#include <sstream>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bench_common.h"
#include "bricklight/gi.h"
#include "bricklight/sdf.h"
#include "gpu_scene.h"
#include "scene_geometry.h"

namespace bricklight::bench {

namespace {

// "downsample" includes the disocclusion mask (pass 2).
const char* const kGiPasses[] = {"downsample",       "clear freed bricks", "inject radiance",   "relight cache",
                                 "propagate SH",     "spawn probes",       "reproject probes",  "fill probes",
                                 "probe world cache", "specular pretrace", "reproject GI",      "specular trace",
                                 "project probes",   "emit irradiance",    "interpolate",       "blur x",
                                 "blur y",           "upsample"};

gi::InternalResolution resolutionOf(uint32_t percent) {
    switch (percent) {
        case 100: return gi::InternalResolution::Native;
        case 75: return gi::InternalResolution::Percent75;
        case 25: return gi::InternalResolution::Percent25;
        default: return gi::InternalResolution::Percent50;
    }
}

// The figures of one run, for the foliage comparison.
struct GiRun {
    double total = 0.0, alphaPass = 0.0;
    PhaseTimes times;
};

// The GI's alpha pass over the scene's alpha-tested triangles (the renderer's shaders and GpuScene).
struct BenchAlphaPass {
    std::unique_ptr<render::GpuScene> scene;
    rhi::ShaderHandle vertex, fragment;
    bool create(rhi::IDevice& device, const scenes::SceneGeometry& geometry) {
        std::string error;
        scene = render::GpuScene::create(device, geometry, &error);
        if (!scene) {
            std::fprintf(stderr, "bricklight-bench: the alpha pass's scene: %s\n", error.c_str());
            return false;
        }
        rhi::ShaderDesc vd, fd;
        vd.blob = rhi::findShader("render/alpha_pass.vert");
        fd.blob = rhi::findShader("render/alpha_pass.frag");
        vertex = vd.blob ? device.createShader(vd) : rhi::ShaderHandle{};
        fragment = fd.blob ? device.createShader(fd) : rhi::ShaderHandle{};
        return vertex && fragment;
    }
    void record(rhi::IDevice& device, gi::GiContext& context) {
        Error error;
        std::optional<rhi::DrawCallState> s = context.alphaPassState(fragment, &error);
        if (!s) {
            std::fprintf(stderr, "bricklight-bench: %s\n", error.message.c_str());
            std::exit(1);
        }
        s->vertexShader = vertex;
        rhi::DrawArgs args;
        scene->bindAlphaPass(*s, &args);
        device.beginMarker("gi alpha pass");
        device.draw(*s, args);
        device.endMarker();
    }
    void destroy(rhi::IDevice& device) {
        for (rhi::ShaderHandle h : {vertex, fragment})
            if (h) device.destroy(h);
        scene.reset();
    }
};

// One benchmark of GI with the alpha-tested meshes entered as `foliage` says (makeBenchScene).
int benchGi(const Options& o, const scenes::SceneGeometry& geometry, std::unique_ptr<rhi::IDevice>& device, const std::string& foliage,
            GiRun* run) {
    const glm::vec3 extent = geometry.boundsMax - geometry.boundsMin;
    const float size = std::max(extent.x, std::max(extent.y, extent.z));
    bool alphaTested = false;
    for (const auto& m : geometry.meshes) alphaTested |= m.alphaTested();
    const bool alphaAware = alphaTested && foliage == "alpha-aware";
    auto scene = makeBenchScene(*device, geometry, o, foliage);
    if (!scene) return 1;
    const sdf::SceneDesc& desc = scene->desc();
    const glm::vec3 centre = geometry.camera.eye;
    for (int i = 0; i < 4; ++i) scene->update(centre), device->endFrame();  // build everything before timing

    gi::ContextDesc cd;
    cd.displayWidth = o.width;
    cd.displayHeight = o.height;
    cd.internalResolution = resolutionOf(o.scalePercent);
    cd.probeTile = o.giProbeTile;
    if (o.giNoCameraCheck) cd.flags |= gi::ContextFlags::NoCameraCheck;
    if (o.giNoProbeParallax) cd.flags |= gi::ContextFlags::NoProbeParallax;
    if (alphaAware) cd.flags |= gi::ContextFlags::AlphaCache;
    Error error;
    auto context = gi::GiContext::create(*device, *scene, cd, &error);
    if (!context) {
        std::fprintf(stderr, "bricklight-bench: %s\n", error.message.c_str());
        return 1;
    }
    using namespace rhi::TextureUsage;
    auto target = [&](rhi::Format f, const char* name) {
        rhi::TextureDesc d;
        d.format = f;
        d.width = o.width;
        d.height = o.height;
        d.usage = Sampled | Storage;
        d.debugName = name;
        return device->createTexture(d);
    };
    BenchGBuffer gbuffer;
    const bool gbufferMade = gbuffer.create(*device, o.width, o.height);
    const rhi::TextureHandle depth = gbuffer.depth, normals = gbuffer.normals, motion = gbuffer.motion, lit = gbuffer.lit;
    rhi::TextureHandle diffuse = target(rhi::Format::RGBA16_FLOAT, "bench diffuse GI"),
                       specular = target(rhi::Format::RGBA16_FLOAT, "bench specular GI");
    // The surfaces' albedo (the G-buffer shader's grey) and its sun, for GI's off-screen relighting.
    rhi::TextureHandle albedo;
    {
        rhi::TextureDesc d;
        d.format = rhi::Format::RGBA16_FLOAT;
        d.width = o.width;
        d.height = o.height;
        d.usage = Sampled;
        d.debugName = "bench albedo";
        const std::vector<uint16_t> grey(size_t(o.width) * o.height * 4, 0x38CD);  // 0.6
        albedo = device->createTexture(d, grey.data());
    }
    gi::Light sun;
    sun.type = gi::LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.4f, 1.0f, 0.3f));
    sun.color = glm::vec3(3.0f * 3.14159265f);  // the G-buffer shader's 0.6 · 3 cos θ = albedo / π · E
    if (!gbufferMade || !albedo || !diffuse || !specular) {
        std::fprintf(stderr, "bricklight-bench: the device could not create the benchmark's G-buffer\n");
        return 1;
    }
    BenchAlphaPass alphaPass;
    if (alphaAware && !alphaPass.create(*device, geometry)) return 1;
    const uint32_t iterations = o.giIterations ? o.giIterations : gi::TraceParams{}.maxIterationsPerCascade;
    const float coarsen = o.giCoarsen >= 0.0f ? o.giCoarsen : gi::TraceParams{}.coarsenAfterVoxels;
    std::printf("scene %s: %llu triangles; %s on %s; %ux%u, GI at %u %% (%ux%u, probe tiles %ux%u); %u cascades, "
                "finest voxel %.4g; GI rays %u steps per cascade, diffuse rays coarsen after %g voxels; alpha-tested meshes %s\n",
                geometry.name.c_str(), (unsigned long long)geometry.triangleCount(), o.backend.c_str(),
                device->capabilities().deviceName.c_str(), o.width, o.height, o.scalePercent, context->internalWidth(),
                context->internalHeight(), context->probeTile(), context->probeTile(), o.cascades, desc.finestVoxelSize,
                iterations, coarsen, alphaTested ? foliage.c_str() : "none");

    const float aspect = float(o.width) / float(o.height);
    BenchCamera previous = cameraAt(geometry.camera, 0.0f, aspect, size);
    auto frame = [&](uint32_t f) {
        const BenchCamera now = cameraAt(geometry.camera, 0.1f * float(f), aspect, size);
        scene->update(centre);
        if (alphaAware) alphaPass.record(*device, *context);
        // This frame's G-buffer, then GI on it (the lit image stands in for last frame's: same cost).
        gi::DispatchDesc d;
        d.camera.view = now.view;
        d.camera.projection = now.projection;
        d.camera.previousView = previous.view;
        d.camera.previousProjection = previous.projection;
        d.cameraPosition = now.eye;
        d.gbuffer.depth = depth;
        d.gbuffer.normals = normals;
        d.gbuffer.normalsUnpackScale = glm::vec3(1.0f);
        d.gbuffer.normalsUnpackOffset = glm::vec3(0.0f);
        d.gbuffer.roughness = normals;
        d.gbuffer.roughnessChannel = 3;
        d.gbuffer.motionVectors = motion;
        d.previousLitOutput = lit;
        d.diffuseAlbedo = albedo;
        d.lights = &sun;
        d.lightCount = 1;
        d.lightUnseenSurfaces = true;  // the costlier configuration: probe rays light what no view has lit
        if (o.giIterations) d.trace.maxIterationsPerCascade = o.giIterations;
        if (o.giCoarsen >= 0.0f) d.trace.coarsenAfterVoxels = o.giCoarsen;
        d.outputDiffuse = diffuse;
        d.outputSpecular = specular;
        gbuffer.record(*device, *scene, now, previous, o.width, o.height);
        if (!context->dispatch(d)) std::exit(1);
        device->endFrame();
        previous = now;
    };
    device->setTimingEnabled(false);
    for (uint32_t f = 0; f < 16; ++f) frame(f);  // warm-up: pipelines, caches, history
    device->waitIdle();
    device->setTimingEnabled(true);
    // Each timed marker's end waits for the work before it: per-pass timing keeps passes from overlapping.
    if (o.giTotalOnly) device->setTimingDepth(1);
    collect(*device, 0);
    const BarrierCounts barriersBefore = barriersSoFar(o, *device);
    for (uint32_t f = 0; f < o.frames; ++f) frame(16 + f);
    const BarrierCounts barriersAfter = barriersSoFar(o, *device);
    const double waitsPerFrame = double(barriersAfter.waits - barriersBefore.waits) / o.frames;
    const double structuresPerFrame = double(barriersAfter.structures - barriersBefore.structures) / o.frames;
    PhaseTimes t = collect(*device, o.frames);

    double total = t.perFrame("gi");
    std::printf("%-24s %9.3f ms/frame (G-buffer %.3f ms, not included)\n", "GI total", total, t.perFrame("bench gbuffer"));
    if (alphaAware) std::printf("  %-22s %9.3f ms (not included: the application draws it)\n", "alpha pass", t.perFrame("gi alpha pass"));
    run->total = total;
    run->alphaPass = t.perFrame("gi alpha pass");
    run->times = t;
    if (o.giTotalOnly) std::printf("  (passes not timed: --timing total)\n");
    else
        for (const char* p : kGiPasses) std::printf("  %-22s %9.3f ms\n", p, t.perFrame(std::string("gi/") + p));
    std::printf("barriers: %.1f a frame, %.1f barrier structures (the G-buffer's and the uploads' included)\n", waitsPerFrame,
                structuresPerFrame);
    const gi::MemoryUse memory = context->memoryUse();
    std::printf("GI memory: %.1f MiB (%.1f MB; without the SDF, and without the two display-size outputs the app owns)\n",
                double(memory.totalBytes) / (1 << 20), double(memory.totalBytes) / 1e6);
    for (const auto& r : memory.resources) std::printf("  %-24s %10.2f MiB\n", r.name.c_str(), double(r.bytes) / (1 << 20));
    const uint32_t slotsInUse = context->radianceCacheBricksInUse();
    std::printf("radiance cache: %u of %u brick slots in use; SDF: %u bricks in use\n", slotsInUse,
                context->desc().radianceCacheBricks ? context->desc().radianceCacheBricks : std::min(scene->brickCapacity(), 65536u),
                scene->latestStats().bricksUsed);
    if (!o.json.empty()) {
        std::ostringstream out;
        out << "{\"technique\": \"gi\", \"scene\": \"" << geometry.name << "\", \"backend\": \"" << o.backend << "\", \"device\": \""
            << device->capabilities().deviceName << "\", \"width\": " << o.width << ", \"height\": " << o.height
            << ", \"scale_percent\": " << o.scalePercent << ", \"iterations_per_cascade\": " << iterations
            << ", \"coarsen_after_voxels\": " << coarsen << ", \"probe_tile\": " << context->probeTile()
            << ", \"total_ms\": " << total << ", \"passes_ms\": {";
        bool first = true;
        for (const char* p : kGiPasses) {
            out << (first ? "" : ", ") << "\"" << p << "\": " << t.perFrame(std::string("gi/") + p);
            first = false;
        }
        out << "}, \"gpu_bytes\": " << memory.totalBytes << ", \"cache_slots_in_use\": " << slotsInUse << "}\n";
        if (!writeJsonReport(o.json, out.str())) return 1;
    }
    for (rhi::TextureHandle h : {albedo, diffuse, specular}) device->destroy(h);
    gbuffer.destroy(*device);
    alphaPass.destroy(*device);
    return 0;
}

}  // namespace

int runGi(const Options& o) {
    scenes::SceneGeometry geometry;
    std::unique_ptr<rhi::IDevice> device;
    if (!openBench(o, &geometry, &device)) return 1;
    bool alphaTested = false;
    for (const auto& m : geometry.meshes) alphaTested |= m.alphaTested();
    GiRun opaque, aware;
    if (!o.giFoliage.empty() || !alphaTested) return benchGi(o, geometry, device, o.giFoliage.empty() ? "opaque" : o.giFoliage, &aware);
    if (!o.json.empty()) {
        std::fprintf(stderr, "bricklight-bench: --json needs --foliage in a scene with alpha-tested meshes (one run per file)\n");
        return 2;
    }
    std::printf("== alpha-tested meshes built opaque\n");
    if (int status = benchGi(o, geometry, device, "opaque", &opaque)) return status;
    std::printf("== alpha-aware (the GI's alpha cache)\n");
    if (int status = benchGi(o, geometry, device, "alpha-aware", &aware)) return status;
    std::printf("foliage: alpha pass %.3f ms; GI %.3f ms against %.3f ms with the cards built opaque (%+.3f ms; continued rays and the\n"
                "  alpha cache's reads and clears), so %+.3f ms in all. Passes that trace:\n",
                aware.alphaPass, aware.total, opaque.total, aware.total - opaque.total, aware.total - opaque.total + aware.alphaPass);
    for (const char* p : {"clear freed bricks", "relight cache", "fill probes", "specular pretrace", "specular trace"}) {
        const std::string label = std::string("gi/") + p;
        std::printf("  %-22s %9.3f ms against %9.3f ms (%+.3f)\n", p, aware.times.perFrame(label), opaque.times.perFrame(label),
                    aware.times.perFrame(label) - opaque.times.perFrame(label));
    }
    return 0;
}

}  // namespace bricklight::bench
