// Shared by the benchmark's techniques: options, devices, and GPU marker timings summed per label.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "bricklight/rhi.h"
#include "bricklight/sdf.h"
#include "scene_geometry.h"

namespace bricklight::bench {

struct Options {
    std::string technique;
    std::string scene;
    std::string backend = "vulkan";
    std::string json;
    uint32_t cascades = 8;
    uint32_t dynamicMaxCascade = 15;
    bool moverGrids = true;  // sdf: rigid movers from mover grids (sdf::SceneDesc::moverGrids)
    uint32_t frames = 16;
    uint32_t width = 1920, height = 1080;
    uint32_t scalePercent = 50;  // gi: internal resolution
    uint32_t giIterations = 0;   // gi: TraceParams::maxIterationsPerCascade (0: GI's default)
    float giCoarsen = -1.0f;     // gi: TraceParams::coarsenAfterVoxels (< 0: GI's default)
    uint32_t giProbeTile = 0;    // gi: ContextDesc::probeTile (0: automatic)
    bool giNoCameraCheck = false;  // gi: ContextFlags::NoCameraCheck
    bool giNoProbeParallax = false;  // gi: ContextFlags::NoProbeParallax
    bool giTotalOnly = false;    // gi: time only the whole GI (passes may overlap; no per-pass figures)
    // gi: how alpha-tested meshes enter the field ("alpha-aware", "opaque", "left-out"); empty: in a scene that has
    // them, opaque then alpha-aware, and the alpha-aware run's extra cost (bench_gi.cpp).
    std::string giFoliage;
    uint32_t vctResolution = 128, vctLevels = 5;  // vct: the clip-map
    std::string vctEmittance = "aniso";           // vct: aniso, iso or none
    uint32_t vctCones = 8, vctSparsity = 2;       // vct: diffuse cones, tracing sparsity
    float vctSpecularJitter = -1.0f;              // vct: ConeTraceParams::specularJitter (< 0: the default)
    float vctTracingStep = -1.0f;                 // vct: ConeTraceParams::tracingStep (< 0: the default)
    bool vctSdfOcclusion = false;                 // vct: cones stop at the distance field's surfaces
    bool vctRegistered = false;                   // vct: voxelize through vct::VoxelScene (culled) instead of one draw
    bool vctCompute = false;                      // vct: ... with its compute voxelizer (vct::Voxelizer::Compute)
    float vctSplitVoxels = 8.0f;                  // vct: vct::ComputeVoxelizer::splitVoxels
    uint32_t classifyTaps = 16;                   // classify: ShadowClassifyDesc::blockerTaps
    bool vctPersistent = false;                   // vct: keep voxels; rewrite what the moving anchor uncovers
    uint32_t vctMoveVoxels = 0;                   // vct: the anchor moves this many finest voxels along x a frame
};

// Sums of GPU milliseconds per marker label over the frames of one phase.
struct PhaseTimes {
    std::map<std::string, double> total;
    uint32_t frames = 0;
    double perFrame(const std::string& label) const {
        auto it = total.find(label);
        return it == total.end() || !frames ? 0.0 : it->second / frames;
    }
};

inline PhaseTimes collect(rhi::IDevice& device, uint32_t frames) {
    device.waitIdle();
    PhaseTimes t;
    t.frames = frames;
    for (const rhi::MarkerTiming& m : device.takeTimings()) t.total[m.label] += m.milliseconds;
    return t;
}

// The benchmark's camera: the scene's, turned by `yawDegrees` about y (the runs pan slowly so that reprojection
// and disocclusion do real work); projection with depth [0, 1] and NDC y = −1 at the top row.
struct BenchCamera {
    glm::mat4 view, projection;
    glm::vec3 eye;
};
BenchCamera cameraAt(const scenes::Camera& c, float yawDegrees, float aspect, float size);

// The G-buffer both GI benchmarks trace through the scene's distance field (examples/bench/shaders/sdf_gbuffer.comp):
// device depth (R32F), normal + roughness, UV motion, a lit image; recorded under the marker "bench gbuffer".
struct BenchGBuffer {
    rhi::TextureHandle depth, normals, motion, lit;
    rhi::ShaderHandle shader;
    bool create(rhi::IDevice& device, uint32_t width, uint32_t height);
    void destroy(rhi::IDevice& device);
    void record(rhi::IDevice& device, sdf::SdfScene& scene, const BenchCamera& now, const BenchCamera& previous, uint32_t width,
                uint32_t height) const;
};

// The device of --backend (null with a message on stderr).
std::unique_ptr<rhi::IDevice> makeDevice(const Options& o);
// Barriers the device of --backend has recorded so far: the points where the GPU may wait for earlier work
// (vkCmdPipelineBarrier2 calls on Vulkan, glMemoryBarrier calls on GL), and on Vulkan the barrier
// structures in them (on GL the same number).
struct BarrierCounts {
    uint64_t waits = 0, structures = 0;
};
BarrierCounts barriersSoFar(const Options& o, rhi::IDevice& device);
// Every technique's start: the scene of --scene and the device of --backend (a warning on stderr when it has
// no GPU timestamps). False with a message on stderr.
bool openBench(const Options& o, scenes::SceneGeometry* geometry, std::unique_ptr<rhi::IDevice>* device);
// Writes a run's --json report (whole or not at all: render::writeFileAtomically) and says so; false with the
// reason printed when it cannot (a full disk, a folder gone since the run began).
bool writeJsonReport(const std::string& path, const std::string& json);

// The scene's distance field with o.cascades cascades, cascade 0 spanning 1/8 of the scene (cascade 3 all
// of it), every mesh and instance added (not built yet). Null with a message on stderr.
// Alpha-tested meshes: registered as alpha-tested with `foliage` "alpha-aware", left out with "left-out", as any
// other mesh otherwise.
std::unique_ptr<sdf::SdfScene> makeBenchScene(rhi::IDevice& device, const scenes::SceneGeometry& geometry, const Options& o,
                                              const std::string& foliage = "opaque");

int runSdf(const Options& o);
int runGi(const Options& o);
int runVct(const Options& o);
int runClassify(const Options& o);
int runReflections(const Options& o);  // bench_reflections.cpp: the second half of `classify`

}  // namespace bricklight::bench
