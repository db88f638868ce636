// bricklight-bench: GPU timings of the techniques, per pass, from GPU timestamps.
//
//   bricklight-bench sdf [--scene NAME|FILE] [--backend vulkan|gl] [--cascades N] [--frames N] [--mover-grids on|off]
//                        [--width W] [--height H] [--json FILE]
//   bricklight-bench gi  [--scene NAME|FILE] [--backend vulkan|gl] [--width W] [--height H] [--scale 100|75|50|25]
//                        [--frames N] [--iterations N] [--coarsen N] [--probe-tile 0|8|16] [--timing passes|total]
//                        [--foliage alpha-aware|opaque|left-out] [--json FILE]
//
// sdf: a full build, frames with one moving ~100k-triangle dynamic instance, with 64 moving ~18k-triangle ones,
// with one ~30k-triangle mesh deforming, frames where the centre moves by one finest voxel, and primary-ray
// trace throughput at W x H (default 1920 x 1080).
// gi: per-pass GPU milliseconds of GI frames at W x H and the internal scale, and GI's memory
// (bench_gi.cpp). Run-time needs: the C++ runtime, the Vulkan loader, libEGL/libGL (assimp only for model
// files).
#include <chrono>
#include <cstdio>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bricklight/gi.h"
#include "bricklight/vct.h"
#include "bricklight/version.h"
#include "bricklight/rhi_gl.h"
#include "bricklight/rhi_vulkan.h"
#include "bench_common.h"
#include "output_file.h"
#include "raster_renderer.h"
#include "bricklight/sdf.h"
#include "scene_geometry.h"

using namespace bricklight;
using namespace bricklight::bench;

namespace {

[[noreturn]] void usage(const std::string& problem) {
    if (!problem.empty()) std::fprintf(stderr, "bricklight-bench: %s\n", problem.c_str());
    std::fprintf(stderr,
                 "usage: bricklight-bench sdf [--scene cornell|field|FILE] [--backend vulkan|gl] [--cascades 1-16]\n"
                 "                            [--frames N] [--width W] [--height H] [--json FILE]\n"
                 "                            [--dynamic-max-cascade C]  (highest cascade of the moving instance)\n"
                 "                            [--mover-grids on|off]  (rigid movers from mover grids, or re-voxelized)\n"
                 "       bricklight-bench gi  [--scene atrium|NAME|FILE] [--backend vulkan|gl] [--width W] [--height H]\n"
                 "                            [--scale 100|75|50|25] [--frames N] [--json FILE]\n"
                 "                            [--iterations N]  (GI rays' steps per cascade; default GI's)\n"
                 "                            [--coarsen N]  (diffuse GI rays' voxels per cascade; 0 off; default GI's)\n"
                 "                            [--probe-tile 0|8|16]  (internal pixels per probe tile side; 0 automatic)\n"
                 "                            [--no-camera-check]  (ContextFlags::NoCameraCheck: its cost measured apart)\n"
                 "                            [--no-probe-parallax]  (ContextFlags::NoProbeParallax: the probes' parallax test off)\n"
                 "                            [--timing passes|total]  (total: time only the whole GI, so that its passes\n"
                 "                             may overlap as they do untimed; default passes)\n"
                 "                            [--foliage alpha-aware|opaque|left-out]  (alpha-tested meshes in the field;\n"
                 "                             default in a scene that has them, e.g. foliage: opaque, then alpha-aware with\n"
                 "                             the GI's alpha pass, and the difference)\n"
                 "       bricklight-bench vct [--scene atrium|NAME|FILE] [--backend vulkan|gl] [--width W] [--height H]\n"
                 "                            [--frames N] [--json FILE] [--resolution 32|64|128|256] [--levels 2-8]\n"
                 "                            [--emittance aniso|iso|none] [--cones 1-32] [--sparsity 1-4]\n"
                 "                            [--occlusion voxels|sdf] [--step PERCENT] [--jitter PERCENT] [--voxelizer draw|scene|compute] [--split VOXELS] [--persistent]\n"
                 "                            [--move VOXELS]  (the anchor's step a frame along x, in finest voxels)\n"
                 "       bricklight-bench classify [--scene atrium|NAME|FILE] [--backend vulkan|gl] [--width W] [--height H]\n"
                 "                            [--frames N] [--cascades N] [--taps 8|16|24|32]  (the shadow classifier and hybrid shadows)\n");
    std::exit(2);
}

uint32_t number(const char* text, const char* option, uint32_t lo, uint32_t hi) {
    char* end = nullptr;
    const unsigned long v = std::strtoul(text, &end, 10);
    if (!*text || *end || v < lo || v > hi)
        usage(std::string(option) + " expects a whole number in " + std::to_string(lo) + ".." + std::to_string(hi));
    return uint32_t(v);
}

Options parse(int argc, char** argv) {
    Options o;
    if (argc < 2) usage("");
    if (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
        std::fflush(stderr);
        std::printf("bricklight-bench sdf|gi|vct|classify [options]: per-pass GPU timings and memory (docs/performance.md); "
                    "exit status 0 measured, 1 the run failed, 2 usage error (bricklight-bench with no arguments lists the options)\n");
        std::exit(0);
    }
    if (std::string(argv[1]) == "--version") {
        std::printf("bricklight-bench %s\n", BRICKLIGHT_VERSION_STRING);
        std::exit(0);
    }
    o.technique = argv[1];
    if (o.technique != "sdf" && o.technique != "gi" && o.technique != "vct" && o.technique != "classify")
        usage("unknown technique '" + o.technique + "' (available: sdf, gi, vct, classify)");
    o.scene = o.technique == "sdf" ? "field" : "atrium";
    for (int i = 2; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&]() -> const char* {
            if (i + 1 >= argc) usage(a + " needs a value");
            return argv[++i];
        };
        if (a == "--scene") o.scene = value();
        else if (a == "--backend") o.backend = value();
        else if (a == "--json") o.json = value();
        else if (a == "--cascades") o.cascades = number(value(), "--cascades", 1, 16);
        else if (a == "--frames") o.frames = number(value(), "--frames", 1, 10000);
        else if (a == "--mover-grids") {
            const std::string v = value();
            if (v != "on" && v != "off") usage("--mover-grids takes on or off");
            o.moverGrids = v == "on";
        } else if (a == "--dynamic-max-cascade") o.dynamicMaxCascade = number(value(), "--dynamic-max-cascade", 0, 15);
        else if (a == "--coarsen") o.giCoarsen = float(number(value(), "--coarsen", 0, 1024));
        else if (a == "--probe-tile") {
            o.giProbeTile = number(value(), "--probe-tile", 0, 16);
            if (o.giProbeTile != 0 && o.giProbeTile != 8 && o.giProbeTile != 16) usage("--probe-tile must be 0, 8 or 16");
        } else if (a == "--no-camera-check") o.giNoCameraCheck = true;
        else if (a == "--no-probe-parallax") o.giNoProbeParallax = true;
        else if (a == "--iterations") o.giIterations = number(value(), "--iterations", 1, gi::kMaxTraceIterations);
        else if (a == "--foliage") {
            o.giFoliage = value();
            if (o.giFoliage != "alpha-aware" && o.giFoliage != "opaque" && o.giFoliage != "left-out")
                usage("--foliage must be alpha-aware, opaque or left-out");
        } else if (a == "--timing") {
            const std::string t = value();
            if (t != "passes" && t != "total") usage("--timing expects passes or total");
            o.giTotalOnly = t == "total";
        } else if (a == "--width") o.width = number(value(), "--width", 1, 16384);
        else if (a == "--height") o.height = number(value(), "--height", 1, 16384);
        else if (a == "--scale") {
            o.scalePercent = number(value(), "--scale", 25, 100);
            if (o.scalePercent != 100 && o.scalePercent != 75 && o.scalePercent != 50 && o.scalePercent != 25)
                usage("--scale must be 100, 75, 50 or 25");
        }
        else if (a == "--resolution") {
            o.vctResolution = number(value(), "--resolution", 32, 256);
            if (o.vctResolution & (o.vctResolution - 1)) usage("--resolution must be 32, 64, 128 or 256");
        } else if (a == "--levels") o.vctLevels = number(value(), "--levels", vct::kMinLevels, vct::kMaxLevels);
        else if (a == "--emittance") {
            o.vctEmittance = value();
            if (o.vctEmittance != "aniso" && o.vctEmittance != "iso" && o.vctEmittance != "none") usage("--emittance must be aniso, iso or none");
        } else if (a == "--cones") o.vctCones = number(value(), "--cones", 1, 32);
        else if (a == "--sparsity") o.vctSparsity = number(value(), "--sparsity", 1, 4);
        else if (a == "--taps") {
            o.classifyTaps = number(value(), "--taps", 8, 32);
            if (o.classifyTaps % 8) usage("--taps must be 8, 16, 24 or 32");
        } else if (a == "--step") o.vctTracingStep = float(number(value(), "--step (percent)", 25, 100)) / 100.0f;
        else if (a == "--jitter") o.vctSpecularJitter = float(number(value(), "--jitter (percent)", 0, 100)) / 100.0f;
        else if (a == "--occlusion") {
            const std::string v = value();
            if (v != "voxels" && v != "sdf") usage("--occlusion must be voxels or sdf");
            o.vctSdfOcclusion = v == "sdf";
        } else if (a == "--voxelizer") {
            const std::string v = value();
            if (v != "draw" && v != "scene" && v != "compute") usage("--voxelizer must be draw, scene or compute");
            o.vctRegistered = v != "draw";
            o.vctCompute = v == "compute";
        } else if (a == "--split") {
            o.vctSplitVoxels = float(number(value(), "--split", 0, 100000));
        } else if (a == "--persistent") {
            o.vctPersistent = true;
        } else if (a == "--move") o.vctMoveVoxels = number(value(), "--move", 0, 64);
        else usage("unknown option '" + a + "'");
    }
    if (o.backend != "vulkan" && o.backend != "gl") usage("--backend must be vulkan or gl");
    // Checked before the run: a report that cannot be written must not cost a benchmark first.
    std::string error;
    if (!o.json.empty() && !render::checkOutputPath(o.json, &error)) usage("--json: " + error);
    return o;
}

// A pass that runs in both of an update's rounds (full, overlay) counts both.
const char* kPasses[] = {"sdf update/invalidate", "sdf update/prepare overlay", "sdf update/gather", "sdf update/count references",
                         "sdf update/allocate bricks", "sdf update/scatter references", "sdf update/emit distances",
                         "sdf update/finalize split bricks", "sdf update/resolve empty", "sdf update/resolve overlay", "sdf trees"};

double updateTotal(const PhaseTimes& t) { return t.perFrame("sdf update") + t.perFrame("sdf trees"); }

void printPhase(const char* name, const PhaseTimes& t) {
    std::printf("%-30s %9.3f ms/frame  (", name, updateTotal(t));
    bool first = true;
    for (const char* p : kPasses) {
        const char* shortName = std::strchr(p, '/') ? std::strchr(p, '/') + 1 : p;
        std::printf("%s%s %.3f", first ? "" : ", ", shortName, t.perFrame(p));
        first = false;
    }
    std::printf(")\n");
}

std::string phaseJson(const PhaseTimes& t) {
    std::string s = "{\"total_ms\": " + std::to_string(updateTotal(t)) + ", \"passes_ms\": {";
    bool first = true;
    for (const char* p : kPasses) {
        s += std::string(first ? "" : ", ") + "\"" + p + "\": " + std::to_string(t.perFrame(p));
        first = false;
    }
    return s + "}}";
}

}  // namespace

std::unique_ptr<rhi::IDevice> bricklight::bench::makeDevice(const Options& o) {
    std::string error;
    std::unique_ptr<rhi::IDevice> device;
    if (o.backend == "vulkan") device = vulkan::createDevice(vulkan::DeviceOptions{});
    else device = gl::createHeadlessDevice(gl::HeadlessApi::Auto, nullptr, &error);
    if (!device)
        std::fprintf(stderr, "bricklight-bench: no %s device%s%s\n", o.backend.c_str(), error.empty() ? "" : ": ", error.c_str());
    return device;
}

bricklight::bench::BarrierCounts bricklight::bench::barriersSoFar(const Options& o, rhi::IDevice& device) {
    // makeDevice's devices are the backends' own, so the counts are always there (value() throws otherwise).
    if (o.backend == "vulkan") return {vulkan::pipelineBarrierCount(device).value(), vulkan::barrierCount(device).value()};
    return {gl::barrierCount(device).value(), gl::barrierCount(device).value()};
}

std::unique_ptr<sdf::SdfScene> bricklight::bench::makeBenchScene(rhi::IDevice& device, const scenes::SceneGeometry& geometry,
                                                                 const Options& o, const std::string& foliage) {
    const glm::vec3 extent = geometry.boundsMax - geometry.boundsMin;
    sdf::SceneDesc desc;
    desc.cascadeCount = o.cascades;
    desc.moverGrids = o.moverGrids;
    // Cascade 0 spans 1/8 of the scene; cascade 3 all of it; the rest reach beyond.
    desc.finestVoxelSize = std::max(extent.x, std::max(extent.y, extent.z)) / 512.0f;
    // The full build of the 1M-triangle field needs ~9M triangle-voxel references (the default budget is
    // 8M, beyond which work is deferred to later updates).
    desc.budgets.maxReferencesPerUpdate =
        uint32_t(std::min<uint64_t>(32u << 20, device.capabilities().limits.maxStorageBufferRange / 12));
    Error error;
    auto scene = sdf::SdfScene::create(device, desc, &error);
    if (!scene) {
        std::fprintf(stderr, "bricklight-bench: %s\n", error.message.c_str());
        return nullptr;
    }
    std::vector<sdf::MeshHandle> meshes;
    for (const auto& m : geometry.meshes)
        meshes.push_back(scene->createMesh({m.positions.data(), uint32_t(m.positions.size() / 3), m.indices.data(),
                                            uint32_t(m.indices.size()), m.name}));
    for (const auto& i : geometry.instances) {
        const bool alphaTested = geometry.meshes[i.mesh].alphaTested();
        if (alphaTested && foliage == "left-out") continue;
        sdf::InstanceDesc d{meshes[i.mesh], i.transform};
        d.alphaTested = alphaTested && foliage == "alpha-aware";
        d.material = render::fieldMaterialOf(geometry.meshes[i.mesh]);  // as the demo renderer registers them
        scene->addInstance(d);
    }
    return scene;
}

bool bricklight::bench::writeJsonReport(const std::string& path, const std::string& json) {
    std::string error;
    const bool written = render::writeFileAtomically(
        path,
        [&](const std::string& temp, std::string* why) {
            std::ofstream out(temp, std::ios::binary | std::ios::trunc);
            out << json;
            out.flush();
            if (!out) *why = "'" + temp + "': " + std::strerror(errno);
            return bool(out);
        },
        nullptr, &error);
    if (!written) {
        std::fprintf(stderr, "bricklight-bench: --json: %s\n", error.c_str());
        return false;
    }
    std::printf("wrote %s\n", path.c_str());
    return true;
}

bool bricklight::bench::openBench(const Options& o, scenes::SceneGeometry* geometry, std::unique_ptr<rhi::IDevice>* device) {
    std::string error;
    *geometry = scenes::loadScene(o.scene, &error);
    if (geometry->meshes.empty()) {
        std::fprintf(stderr, "bricklight-bench: %s\n", error.c_str());
        return false;
    }
    *device = makeDevice(o);
    if (!*device) return false;
    if (!(*device)->capabilities().timestamps) std::fprintf(stderr, "bricklight-bench: warning: the device has no GPU timestamps\n");
    return true;
}

int bricklight::bench::runSdf(const Options& o) {
    scenes::SceneGeometry geometry;
    std::unique_ptr<rhi::IDevice> device;
    if (!openBench(o, &geometry, &device)) return 1;
    device->setTimingEnabled(true);

    const glm::vec3 extent = geometry.boundsMax - geometry.boundsMin;
    const float size = std::max(extent.x, std::max(extent.y, extent.z));
    auto scene = makeBenchScene(*device, geometry, o);
    if (!scene) return 1;
    const sdf::SceneDesc& desc = scene->desc();
    const glm::vec3 center = (geometry.boundsMin + geometry.boundsMax) * 0.5f + glm::vec3(0.0f, 0.05f * size, 0.0f);
    std::printf("scene %s: %llu triangles in %zu instances; %s on %s; %u cascades, finest voxel %.4g\n", geometry.name.c_str(),
                (unsigned long long)geometry.triangleCount(), geometry.instances.size(), o.backend.c_str(),
                device->capabilities().deviceName.c_str(), o.cascades, desc.finestVoxelSize);

    // 1. Full build (shaders and pipelines warmed by a first, untimed build of the same scene).
    device->setTimingEnabled(false);
    scene->update(center);
    device->waitIdle();
    scene->invalidateAll();
    device->setTimingEnabled(true);
    device->takeTimings();
    const auto wallStart = std::chrono::steady_clock::now();
    sdf::UpdateReport full = scene->update(center);
    device->endFrame();
    PhaseTimes build = collect(*device, 1);
    const double wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wallStart).count();
    for (int i = 0; i < 4; ++i) scene->update(center), device->endFrame();  // let the stats arrive
    device->waitIdle();
    scene->update(center);
    const sdf::Stats afterBuild = scene->latestStats();

    // 2. One moving dynamic instance of ~100k triangles, 16 finest voxels across (a character-sized object
    //    when the finest voxel is ~10 cm).
    const float vs0 = desc.finestVoxelSize;
    scenes::TriangleMesh ring = scenes::torus(6.0f * vs0, 2.0f * vs0, 100000);
    sdf::MeshHandle ringMesh = scene->createMesh({ring.positions.data(), uint32_t(ring.positions.size() / 3), ring.indices.data(),
                                                  uint32_t(ring.indices.size()), "moving torus"});
    auto ringAt = [&](uint32_t frame) {
        return glm::rotate(glm::translate(glm::mat4(1.0f), center + glm::vec3(0.5f * vs0 * float(frame), 0.0f, 0.0f)),
                           0.05f * float(frame), glm::vec3(0.2f, 1.0f, 0.1f));
    };
    sdf::InstanceHandle moving = scene->addInstance({ringMesh, ringAt(0), true, o.dynamicMaxCascade});
    scene->update(center);  // builds its mover grid (once per mesh and scale)
    device->endFrame();
    PhaseTimes gridBuild = collect(*device, 1);
    for (uint32_t f = 1; f < 3; ++f) scene->setTransform(moving, ringAt(f)), scene->update(center), device->endFrame();
    collect(*device, 0);
    for (uint32_t f = 0; f < o.frames; ++f) {
        scene->setTransform(moving, ringAt(3 + f));
        scene->update(center);
        device->endFrame();
    }
    PhaseTimes dynamicFrames = collect(*device, o.frames);
    scene->update(center);  // polls the read-back of the last measured frame
    const sdf::Stats dynamicStats = scene->latestStats();
    scene->removeInstance(moving);
    scene->update(center);
    device->endFrame();
    collect(*device, 0);

    // 2b. 64 rigid dynamic instances of ~18k triangles (4 finest voxels across), 8 x 8 around the centre, all
    //     moving every frame.
    scenes::TriangleMesh prop = scenes::torus(1.5f * vs0, 0.5f * vs0, 18000);
    sdf::MeshHandle propMesh = scene->createMesh({prop.positions.data(), uint32_t(prop.positions.size() / 3), prop.indices.data(),
                                                  uint32_t(prop.indices.size()), "rigid prop"});
    auto propAt = [&](uint32_t i, uint32_t frame) {
        const glm::vec3 offset(6.0f * vs0 * (float(i % 8) - 3.5f), 0.0f, 6.0f * vs0 * (float(i / 8) - 3.5f));
        return glm::rotate(glm::translate(glm::mat4(1.0f), center + offset + glm::vec3(0.25f * vs0 * float(frame), 0.0f, 0.0f)),
                           0.05f * float(frame + i), glm::vec3(0.2f, 1.0f, 0.1f));
    };
    std::vector<sdf::InstanceHandle> props;
    for (uint32_t i = 0; i < 64; ++i) props.push_back(scene->addInstance({propMesh, propAt(i, 0), true, o.dynamicMaxCascade}));
    for (uint32_t f = 0; f < 3; ++f) {
        for (uint32_t i = 0; i < 64; ++i) scene->setTransform(props[i], propAt(i, f));
        scene->update(center), device->endFrame();
    }
    collect(*device, 0);
    for (uint32_t f = 0; f < o.frames; ++f) {
        for (uint32_t i = 0; i < 64; ++i) scene->setTransform(props[i], propAt(i, 3 + f));
        scene->update(center);
        device->endFrame();
    }
    PhaseTimes rigidFrames = collect(*device, o.frames);
    scene->update(center);
    const sdf::Stats rigidStats = scene->latestStats();
    for (sdf::InstanceHandle h : props) scene->removeInstance(h);
    scene->update(center);
    device->endFrame();
    collect(*device, 0);

    // 2c. One deforming mesh of ~30k triangles (8 finest voxels across) in a buffer of the application's, its
    //     positions rewritten every frame (the upload is a transfer, outside the field's timings).
    scenes::TriangleMesh blob = scenes::torus(3.0f * vs0, 1.0f * vs0, 30000);
    auto blobPositions = [&](uint32_t frame) {
        std::vector<float> p = blob.positions;
        for (size_t v = 0; v < p.size(); v += 3) p[v + 1] *= 1.0f + 0.4f * std::sin(0.7f * float(frame) + 2.0f * p[v] / vs0);
        return p;
    };
    rhi::BufferHandle blobVertices = device->createBuffer(
        {blob.positions.size() * 4, 0, rhi::BufferUsage::ShaderRead, "deforming positions"}, blobPositions(0).data());
    rhi::BufferHandle blobIndices =
        device->createBuffer({blob.indices.size() * 4, 0, rhi::BufferUsage::ShaderRead, "deforming indices"}, blob.indices.data());
    sdf::MeshBuffers blobBuffers;
    blobBuffers.vertexBuffer = blobVertices;
    blobBuffers.vertexCount = uint32_t(blob.positions.size() / 3);
    blobBuffers.indexBuffer = blobIndices;
    blobBuffers.triangleCount = uint32_t(blob.indices.size() / 3);
    blobBuffers.boundsMin = glm::vec3(-4.0f * vs0, -1.4f * vs0, -4.0f * vs0);
    blobBuffers.boundsMax = glm::vec3(4.0f * vs0, 1.4f * vs0, 4.0f * vs0);
    blobBuffers.name = "deforming torus";
    sdf::MeshHandle blobMesh = scene->createMesh(blobBuffers);
    sdf::InstanceHandle deforming =
        scene->addInstance({blobMesh, glm::translate(glm::mat4(1.0f), center), true, o.dynamicMaxCascade});
    auto deformTo = [&](uint32_t frame) {
        const std::vector<float> p = blobPositions(frame);
        device->writeBuffer(blobVertices, 0, p.data(), p.size() * 4);
    };
    for (uint32_t f = 0; f < 3; ++f) deformTo(f), scene->update(center), device->endFrame();
    collect(*device, 0);
    for (uint32_t f = 0; f < o.frames; ++f) {
        deformTo(3 + f);
        scene->update(center);
        device->endFrame();
    }
    PhaseTimes deformingFrames = collect(*device, o.frames);
    scene->update(center);
    const sdf::Stats deformingStats = scene->latestStats();
    scene->removeInstance(deforming);
    scene->update(center);
    device->endFrame();
    collect(*device, 0);

    // 3. The centre moves by one finest voxel per frame.
    glm::vec3 c = center;
    for (uint32_t f = 0; f < o.frames; ++f) {
        c.x += desc.finestVoxelSize;
        scene->update(c);
        device->endFrame();
    }
    PhaseTimes scrollFrames = collect(*device, o.frames);
    scene->update(c);
    const sdf::Stats scrollStats = scene->latestStats();

    // 4. Primary rays through the trace API.
    struct {
        glm::mat4 inverseViewProjection;
        glm::vec4 eye;
        uint32_t size[4];
    } p{};
    const glm::vec3 eye = c + glm::vec3(0.0f, 0.02f * size, -0.3f * size);
    const glm::mat4 view = glm::lookAt(eye, c + glm::vec3(0.0f, -0.02f * size, 0.0f), glm::vec3(0, 1, 0));
    const glm::mat4 proj = glm::perspectiveRH_ZO(glm::radians(60.0f), float(o.width) / float(o.height), 0.01f, 10.0f * size);
    p.inverseViewProjection = glm::inverse(proj * view);
    p.eye = glm::vec4(eye, 1.0f);
    p.size[0] = o.width;
    p.size[1] = o.height;
    rhi::BufferHandle depth = device->createBuffer({uint64_t(o.width) * o.height * 4, 0,
                                                    rhi::BufferUsage::ShaderRead | rhi::BufferUsage::ShaderWrite, "depth"});
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("bench/primary_rays.comp");
    rhi::ShaderHandle tracer = device->createShader(sd);
    rhi::DispatchState s;
    s.shader = tracer;
    s.label = "primary rays";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.storageBuffers.push({0, depth, {}, rhi::Access::Write});
    scene->traceBindings(s.bindings, {});
    device->dispatch(s, (o.width + 7) / 8, (o.height + 7) / 8, 1);  // warm-up
    collect(*device, 0);
    for (uint32_t f = 0; f < o.frames; ++f) {
        device->beginMarker("trace");
        device->dispatch(s, (o.width + 7) / 8, (o.height + 7) / 8, 1);
        device->endMarker();
        device->endFrame();
    }
    PhaseTimes trace = collect(*device, o.frames);
    std::vector<float> depths(size_t(o.width) * o.height);
    device->readBuffer(depth, 0, depths.size() * 4, depths.data());
    size_t hits = 0;
    for (float d : depths) hits += d >= 0.0f;
    const double traceMs = trace.perFrame("trace");
    const double raysPerSecond = traceMs > 0 ? double(o.width) * o.height / (traceMs * 1e-3) : 0.0;

    std::printf("%-30s %9.3f ms (wall %.1f ms; %u voxels in %u jobs, %u triangles gathered)\n", "full build: total", updateTotal(build),
                wallMs, full.voxels, full.jobs, full.trianglesGathered);
    printPhase("full build", build);
    if (o.moverGrids) std::printf("%-30s %9.3f ms (once, with its first update)\n", "mover grid 100k: build", gridBuild.perFrame("build mover grids"));
    printPhase(("moving dynamic 100k (to c" + std::to_string(std::min(o.dynamicMaxCascade, o.cascades - 1)) + ")").c_str(), dynamicFrames);
    std::printf("%-30s last frame: %u bricks built, %u triangles, %u references\n", "", dynamicStats.bricksAllocated,
                dynamicStats.trianglesProcessed, dynamicStats.referencesProcessed);
    printPhase(("moving rigid x64 (to c" + std::to_string(std::min(o.dynamicMaxCascade, o.cascades - 1)) + ")").c_str(), rigidFrames);
    std::printf("%-30s last frame: %u bricks built, %u triangles, %u references\n", "", rigidStats.bricksAllocated,
                rigidStats.trianglesProcessed, rigidStats.referencesProcessed);
    printPhase(("deforming 30k (to c" + std::to_string(std::min(o.dynamicMaxCascade, o.cascades - 1)) + ")").c_str(), deformingFrames);
    std::printf("%-30s last frame: %u bricks built, %u triangles, %u references\n", "", deformingStats.bricksAllocated,
                deformingStats.trianglesProcessed, deformingStats.referencesProcessed);
    printPhase("centre moves one voxel", scrollFrames);
    std::printf("%-30s last frame: %u bricks built, %u triangles, %u references\n", "", scrollStats.bricksAllocated,
                scrollStats.trianglesProcessed, scrollStats.referencesProcessed);
    std::printf("%-30s %9.3f ms/frame  = %.3f G rays/s at %ux%u (%.1f%% hit)\n", "primary rays", traceMs, raysPerSecond * 1e-9,
                o.width, o.height, 100.0 * double(hits) / double(depths.size()));
    std::printf("bricks: %u used of %u (%u free), %u triangles and %u references processed by the full build\n",
                afterBuild.bricksUsed, afterBuild.bricksCapacity, afterBuild.bricksFree, afterBuild.trianglesProcessed,
                afterBuild.referencesProcessed);
    const sdf::MemoryUse memory = scene->memoryUse();
    std::printf("GPU memory: %.1f MiB\n", double(memory.totalBytes) / (1 << 20));
    for (const auto& r : memory.resources) std::printf("  %-32s %10.2f MiB\n", r.name.c_str(), double(r.bytes) / (1 << 20));

    if (!o.json.empty()) {
        std::ostringstream out;
        out << "{\"technique\": \"sdf\", \"scene\": \"" << geometry.name << "\", \"backend\": \"" << o.backend
            << "\", \"device\": \"" << device->capabilities().deviceName << "\", \"triangles\": " << geometry.triangleCount()
            << ", \"cascades\": " << o.cascades << ", \"finest_voxel\": " << desc.finestVoxelSize
            << ",\n \"full_build\": " << phaseJson(build) << ",\n \"dynamic_100k\": " << phaseJson(dynamicFrames)
            << ",\n \"rigid_x64\": " << phaseJson(rigidFrames) << ",\n \"deforming_30k\": " << phaseJson(deformingFrames)
            << ",\n \"scroll_one_voxel\": " << phaseJson(scrollFrames) << ",\n \"trace\": {\"ms\": " << traceMs
            << ", \"rays_per_second\": " << raysPerSecond << ", \"width\": " << o.width << ", \"height\": " << o.height
            << "},\n \"bricks_used\": " << afterBuild.bricksUsed << ", \"references\": " << afterBuild.referencesProcessed
            << ", \"gpu_bytes\": " << memory.totalBytes << "}\n";
        if (!writeJsonReport(o.json, out.str())) return 1;
    }
    device->destroy(depth);
    device->destroy(tracer);
    device->destroy(blobVertices);
    device->destroy(blobIndices);
    return 0;
}

int main(int argc, char** argv) {
    Options o = parse(argc, argv);
    return o.technique == "gi" ? runGi(o) : o.technique == "vct" ? runVct(o) : o.technique == "classify" ? (runClassify(o) ? 1 : runReflections(o)) : runSdf(o);
}
