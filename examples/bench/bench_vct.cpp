// bricklight-bench vct: GPU milliseconds per voxel cone tracing pass and the clip-map's memory. Every frame
// revoxelizes the whole clip-map (opacity and emittance in one pass of the scene's triangles through
// vct::Clipmap::voxelizationState, then downsampling and the traced volumes), then traces diffuse and specular
// cones on a G-buffer traced through the scene's distance field (timed apart); then the same for voxel AO
// (an opacity-only clip-map). The clip-map follows the camera; its coarsest level spans twice the scene.
// --voxelizer scene registers the meshes with a vct::VoxelScene (culled draws); compute does too, voxelized by
// its compute voxelizer (vct::Voxelizer::Compute).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "bench_common.h"
#include "bricklight/vct.h"
#include "bricklight/vct_scene.h"
#include "scene_geometry.h"

namespace bricklight::bench {

namespace {

const char* const kVctPasses[] = {"vct update", "vct voxelize", "vct resolve", "vct downsample", "vct borders", "vct mips", "vct diffuse", "vct specular"};

// The scene's triangles in world space, 3 vertices each: position, normal (the triangle's own where the mesh
// has none).
std::vector<float> worldTriangles(const scenes::SceneGeometry& g) {
    std::vector<float> out;
    out.reserve(size_t(g.triangleCount()) * 18);
    for (const scenes::MeshInstance& inst : g.instances) {
        const scenes::TriangleMesh& m = g.meshes[inst.mesh];
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(inst.transform)));
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            glm::vec3 p[3], n[3];
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = m.indices[t + size_t(k)];
                p[k] = glm::vec3(inst.transform * glm::vec4(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2], 1.0f));
                if (m.normals.size() >= 3 * size_t(v) + 3) n[k] = normalMatrix * glm::vec3(m.normals[3 * v], m.normals[3 * v + 1], m.normals[3 * v + 2]);
            }
            const glm::vec3 face = glm::cross(p[1] - p[0], p[2] - p[0]);
            for (int k = 0; k < 3; ++k) {
                if (m.normals.empty()) n[k] = face;
                const glm::vec3 nn = glm::length(n[k]) > 0.0f ? glm::normalize(n[k]) : glm::vec3(0, 1, 0);
                out.insert(out.end(), {p[k].x, p[k].y, p[k].z, nn.x, nn.y, nn.z});
            }
        }
    }
    return out;
}

// The compute voxelizer (--voxelizer compute; --split: ComputeVoxelizer::splitVoxels).
struct ComputeChoice {
    bool enabled = false;
    vct::ComputeVoxelizer options;
};
ComputeChoice computeChoice(const Options& o) {
    ComputeChoice c;
    c.enabled = o.vctCompute;
    c.options.splitVoxels = o.vctSplitVoxels;
    return c;
}

vct::EmittanceMode modeOf(const std::string& s) {
    return s == "none" ? vct::EmittanceMode::None : s == "iso" ? vct::EmittanceMode::Isotropic : vct::EmittanceMode::Anisotropic;
}

}  // namespace

int runVct(const Options& o) {
    scenes::SceneGeometry geometry;
    std::unique_ptr<rhi::IDevice> device;
    if (!openBench(o, &geometry, &device)) return 1;
    const glm::vec3 extent = geometry.boundsMax - geometry.boundsMin;
    const float size = std::max(extent.x, std::max(extent.y, extent.z));
    auto scene = makeBenchScene(*device, geometry, o);
    if (!scene) return 1;
    for (int i = 0; i < 4; ++i) scene->update(geometry.camera.eye), device->endFrame();  // the G-buffer's field

    BenchGBuffer gbuffer;
    rhi::TextureDesc td;
    td.format = rhi::Format::RGBA16_FLOAT;
    td.width = o.width;
    td.height = o.height;
    td.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::Storage;
    td.debugName = "bench vct diffuse";
    const rhi::TextureHandle diffuse = device->createTexture(td);
    td.debugName = "bench vct specular";
    const rhi::TextureHandle specular = device->createTexture(td);
    const std::vector<float> vertices = worldTriangles(geometry);
    rhi::BufferDesc bd;
    bd.size = vertices.size() * sizeof(float);
    bd.usage = rhi::BufferUsage::Vertex;
    bd.debugName = "bench vct triangles";
    const rhi::BufferHandle vertexBuffer = device->createBuffer(bd, vertices.data());
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("bench/vct_voxelize.vert");
    const rhi::ShaderHandle vertexShader = sd.blob ? device->createShader(sd) : rhi::ShaderHandle{};
    sd.blob = rhi::findShader("bench/vct_emittance.frag");
    const rhi::ShaderHandle emittanceShader = sd.blob ? device->createShader(sd) : rhi::ShaderHandle{};
    // The same emittance for the compute voxelizer (bricklight/voxelize_compute.glsl).
    const ComputeChoice compute = computeChoice(o);
    sd.blob = compute.enabled ? rhi::findShader("bench/vct_emittance.comp") : nullptr;
    const rhi::ShaderHandle emittanceCompute = sd.blob ? device->createShader(sd) : rhi::ShaderHandle{};
    if (!gbuffer.create(*device, o.width, o.height) || !diffuse || !specular || !vertexBuffer || !vertexShader || !emittanceShader) {
        std::fprintf(stderr, "bricklight-bench: the device could not create the benchmark's G-buffer or voxelization inputs\n");
        return 1;
    }
    const uint32_t vertexCount = uint32_t(vertices.size() / 6);
    const float aspect = float(o.width) / float(o.height);
    // The benchmark G-buffer's sun (sdf_gbuffer.comp): a grey 0.6 surface under 3 cos θ.
    const struct {
        glm::vec4 direction, radiance;
    } sun{glm::vec4(glm::normalize(glm::vec3(-0.4f, 1.0f, 0.3f)), 0.0f), glm::vec4(glm::vec3(0.6f * 3.0f), 0.0f)};

    // One run: a clip-map of `mode`, every frame revoxelized and traced; returns its per-pass times.
    auto run = [&](vct::EmittanceMode mode, PhaseTimes* times, vct::MemoryUse* memory, uint64_t* voxelsWritten) -> bool {
        vct::ClipmapDesc desc;
        desc.resolution = o.vctResolution;
        desc.levels = o.vctLevels;
        desc.emittance = mode;
        desc.persistent = o.vctPersistent;
        desc.finestVoxelSize = 2.0f * size / float(desc.resolution * (1u << (desc.levels - 1)));
        Error error;
        auto clipmap = vct::Clipmap::create(*device, desc, &error);
        auto tracer = clipmap ? vct::ConeTracer::create(*device, *clipmap, {o.width, o.height}, &error) : nullptr;
        if (!tracer) {
            std::fprintf(stderr, "bricklight-bench: %s\n", error.message.c_str());
            return false;
        }
        vct::VoxelMaterial material;
        material.fragmentShader = mode == vct::EmittanceMode::None ? rhi::ShaderHandle{} : emittanceShader;
        material.computeShader = mode == vct::EmittanceMode::None ? rhi::ShaderHandle{} : emittanceCompute;
        std::optional<rhi::DrawCallState> state = clipmap->voxelizationState(material, &error);
        if (!state) {
            std::fprintf(stderr, "bricklight-bench: %s\n", error.message.c_str());
            return false;
        }
        // --voxelizer scene: the scene's meshes and instances registered with a vct::VoxelScene, which draws only
        // the instances that meet this update's rewrite regions; compute: the same, voxelized in compute.
        std::unique_ptr<vct::VoxelScene> voxelScene;
        if (o.vctRegistered || compute.enabled) {
            voxelScene = vct::VoxelScene::create(*device, &error);
            if (voxelScene && compute.enabled) voxelScene->setVoxelizer(vct::Voxelizer::Compute, compute.options);
            std::vector<vct::VoxelMeshHandle> meshes;
            for (const scenes::TriangleMesh& m : geometry.meshes) {
                vct::VoxelMeshArrays a{m.positions.data(), m.normals.empty() ? nullptr : m.normals.data(), uint32_t(m.positions.size() / 3),
                                       m.indices.data(), uint32_t(m.indices.size()), m.name};
                meshes.push_back(voxelScene ? voxelScene->createMesh(a, &error) : vct::VoxelMeshHandle{});
                if (!meshes.back()) break;
            }
            for (const scenes::MeshInstance& i : geometry.instances)
                if (!voxelScene || !meshes.back() || !voxelScene->addInstance({meshes[i.mesh], i.transform, material, {}, {}}, &error)) {
                    std::fprintf(stderr, "bricklight-bench: %s\n", error.message.c_str());
                    return false;
                }
        }
        uint64_t drawsPerFrame = 0, computesPerFrame = 0;  // instances voxelized (of them in compute) over the timed frames
        rhi::Bindings sunBindings;
        if (material.fragmentShader) sunBindings.constants.push(rhi::constants(0, sun));
        state->vertexShader = vertexShader;
        state->vertexInputs.push({0, rhi::VertexFormat::Float3, 0, 0});
        state->vertexInputs.push({1, rhi::VertexFormat::Float3, 0, 12});
        state->vertexBuffers.push({vertexBuffer, 0, 24, false});
        if (material.fragmentShader) state->bindings.constants.push(rhi::constants(0, sun));
        vct::ConeTraceParams params;
        params.diffuseCones = o.vctCones;
        params.tracingSparsity = o.vctSparsity;
        if (o.vctSpecularJitter >= 0.0f) params.specularJitter = o.vctSpecularJitter;
        if (o.vctTracingStep > 0.0f) params.tracingStep = o.vctTracingStep;
        BenchCamera previous = cameraAt(geometry.camera, 0.0f, aspect, size);
        auto frame = [&](uint32_t f) {
            const BenchCamera now = cameraAt(geometry.camera, 0.1f * float(f), aspect, size);
            scene->update(geometry.camera.eye);
            gbuffer.record(*device, *scene, now, previous, o.width, o.height);
            // Top-level markers only: a nested marker's label would be "outer/inner".
            device->beginMarker("vct update");
            const glm::vec3 anchor = now.eye + glm::vec3(float(o.vctMoveVoxels * f) * desc.finestVoxelSize, 0.0f, 0.0f);
            clipmap->update(anchor, &error, voxelScene ? voxelScene->takeDirtyRegions() : std::vector<vct::WorldBox>{});
            device->endMarker();
            device->beginMarker("vct voxelize");
            if (voxelScene) {
                voxelScene->voxelize(*clipmap, sunBindings, &error);
                drawsPerFrame += voxelScene->lastDrawCount();
                computesPerFrame += voxelScene->lastComputeCount();
            } else if (!clipmap->rewriteBoxes().empty()) {
                rhi::DrawArgs args;
                args.vertexCount = vertexCount;
                device->draw(*state, args);
                drawsPerFrame += 1;
            }
            device->endMarker();
            clipmap->finishVoxelization();
            vct::TraceDesc t;
            t.camera.view = now.view;
            t.camera.projection = now.projection;
            t.camera.previousView = previous.view;
            t.camera.previousProjection = previous.projection;
            t.cameraPosition = now.eye;
            t.gbuffer.depth = gbuffer.depth;
            t.gbuffer.normals = gbuffer.normals;
            t.gbuffer.normalsUnpackScale = glm::vec3(1.0f);  // float normals
            t.gbuffer.normalsUnpackOffset = glm::vec3(0.0f);
            t.gbuffer.roughness = gbuffer.normals;
            t.gbuffer.roughnessChannel = 3;
            t.gbuffer.motionVectors = gbuffer.motion;
            t.outputDiffuse = diffuse;
            t.outputSpecular = mode == vct::EmittanceMode::None ? rhi::TextureHandle{} : specular;
            t.params = params;
            t.occlusionField = o.vctSdfOcclusion ? scene.get() : nullptr;
            if (!tracer->dispatch(t, &error)) {
                std::fprintf(stderr, "bricklight-bench: %s\n", error.message.c_str());
                std::exit(1);
            }
            device->endFrame();
            previous = now;
        };
        device->setTimingEnabled(false);
        for (uint32_t f = 0; f < 8; ++f) frame(f);  // warm-up
        device->waitIdle();
        device->setTimingEnabled(true);
        collect(*device, 0);
        clipmap->setCountersEnabled(true);
        clipmap->resetCounters();
        drawsPerFrame = computesPerFrame = 0;
        for (uint32_t f = 0; f < o.frames; ++f) frame(8 + f);
        std::printf("  (%s, %s) voxelization draws a frame: %.1f\n", mode == vct::EmittanceMode::None ? "AO" : "GI",
                    compute.enabled ? "registered meshes, culled, compute voxelizer"
                    : voxelScene    ? "registered meshes, culled"
                                    : "one draw of every triangle",
                    double(drawsPerFrame) / o.frames);
        if (compute.enabled)
            std::printf("  (%s) instances voxelized in compute a frame: %.1f (split above %g voxels; the rest drawn%s)\n",
                        mode == vct::EmittanceMode::None ? "AO" : "GI", double(computesPerFrame) / o.frames, double(compute.options.splitVoxels),
                        mode != vct::EmittanceMode::None && !emittanceCompute ? ": no bench/vct_emittance.comp in this build" : "");
        *times = collect(*device, o.frames);
        const vct::VoxelizationCounters counters = clipmap->readCounters();
        *voxelsWritten = counters.voxelsWritten / o.frames;
        if (mode != vct::EmittanceMode::None)  // the latest update's (the pool starts over each update)
            std::printf("  (GI) light entries claimed by the latest update: %llu of %llu, light writes dropped: %llu\n",
                        (unsigned long long)counters.lightEntriesClaimed, (unsigned long long)counters.lightEntriesAvailable,
                        (unsigned long long)counters.lightDropped);
        clipmap->setCountersEnabled(false);
        vct::MemoryUse m = clipmap->memoryUse(), tm = tracer->memoryUse();
        m.resources.insert(m.resources.end(), tm.resources.begin(), tm.resources.end());
        m.totalBytes += tm.totalBytes;
        *memory = m;
        device->setTimingEnabled(false);
        return true;
    };

    std::printf("scene %s: %llu triangles; %s on %s; %ux%u; clip-map %u^3 x %u levels, finest voxel %.4g, emittance %s; %u diffuse "
                "cones, sparsity %u, step %.2f, occlusion %s\n",
                geometry.name.c_str(), (unsigned long long)geometry.triangleCount(), o.backend.c_str(), device->capabilities().deviceName.c_str(),
                o.width, o.height, o.vctResolution, o.vctLevels, 2.0f * size / float(o.vctResolution * (1u << (o.vctLevels - 1))),
                o.vctEmittance.c_str(), o.vctCones, o.vctSparsity,
                double(o.vctTracingStep > 0.0f ? o.vctTracingStep : vct::ConeTraceParams{}.tracingStep), o.vctSdfOcclusion ? "sdf" : "voxels");
    PhaseTimes gi, ao;
    vct::MemoryUse giMemory, aoMemory;
    uint64_t giVoxels = 0, aoVoxels = 0;
    if (!run(modeOf(o.vctEmittance), &gi, &giMemory, &giVoxels) || !run(vct::EmittanceMode::None, &ao, &aoMemory, &aoVoxels)) return 1;
    const double revoxelize = gi.perFrame("vct update") + gi.perFrame("vct voxelize") + gi.perFrame("vct resolve") + gi.perFrame("vct downsample") + gi.perFrame("vct borders") +
                              gi.perFrame("vct mips");
    const double tracing = gi.perFrame("vct diffuse") + gi.perFrame("vct specular");
    std::printf("GI: full revoxelization %.3f ms, diffuse + specular %.3f ms (G-buffer %.3f ms, not included); %llu voxel writes a frame\n",
                revoxelize, tracing, gi.perFrame("bench gbuffer"), (unsigned long long)giVoxels);
    for (const char* p : kVctPasses) std::printf("  %-22s %9.3f ms\n", p, gi.perFrame(p));
    const double aoVoxelize = ao.perFrame("vct update") + ao.perFrame("vct voxelize") + ao.perFrame("vct resolve") + ao.perFrame("vct downsample") + ao.perFrame("vct borders") +
                              ao.perFrame("vct mips");
    std::printf("voxel AO: revoxelization (opacity only) %.3f ms, AO tracing %.3f ms\n", aoVoxelize, ao.perFrame("vct diffuse"));
    for (const char* p : kVctPasses) std::printf("  %-22s %9.3f ms\n", p, ao.perFrame(p));
    std::printf("memory: GI %.1f MiB, voxel AO %.1f MiB (clip-map and tracer; the two outputs are the app's)\n",
                double(giMemory.totalBytes) / (1 << 20), double(aoMemory.totalBytes) / (1 << 20));
    for (const auto& r : giMemory.resources) std::printf("  %-28s %10.2f MiB\n", r.name.c_str(), double(r.bytes) / (1 << 20));
    std::printf("clip-map memory per configuration (vct::clipmapBytes, MiB): resolution x levels: anisotropic / isotropic / AO\n");
    for (uint32_t res : {64u, 128u, 256u})
        for (uint32_t levels : {3u, 5u}) {
            vct::ClipmapDesc d;
            d.resolution = res;
            d.levels = levels;
            double mib[3];
            int i = 0;
            for (vct::EmittanceMode m : {vct::EmittanceMode::Anisotropic, vct::EmittanceMode::Isotropic, vct::EmittanceMode::None}) {
                d.emittance = m;
                mib[i++] = double(vct::clipmapBytes(d)) / (1 << 20);
            }
            std::printf("  %3u^3 x %u: %9.1f / %8.1f / %7.1f\n", res, levels, mib[0], mib[1], mib[2]);
        }
    if (!o.json.empty()) {
        std::ostringstream out;
        out << "{\"technique\": \"vct\", \"scene\": \"" << geometry.name << "\", \"backend\": \"" << o.backend << "\", \"device\": \""
            << device->capabilities().deviceName << "\", \"width\": " << o.width << ", \"height\": " << o.height
            << ", \"resolution\": " << o.vctResolution << ", \"levels\": " << o.vctLevels << ", \"revoxelize_ms\": " << revoxelize
            << ", \"trace_ms\": " << tracing << ", \"ao_trace_ms\": " << ao.perFrame("vct diffuse") << ", \"passes_ms\": {";
        bool first = true;
        for (const char* p : kVctPasses) {
            out << (first ? "" : ", ") << "\"" << p << "\": " << gi.perFrame(p);
            first = false;
        }
        out << "}, \"gpu_bytes\": " << giMemory.totalBytes << ", \"ao_gpu_bytes\": " << aoMemory.totalBytes << "}\n";
        if (!writeJsonReport(o.json, out.str())) return 1;
    }
    for (rhi::TextureHandle h : {diffuse, specular}) device->destroy(h);
    device->destroy(vertexBuffer);
    device->destroy(vertexShader);
    device->destroy(emittanceShader);
    if (emittanceCompute) device->destroy(emittanceCompute);
    gbuffer.destroy(*device);
    return 0;
}

}  // namespace bricklight::bench
