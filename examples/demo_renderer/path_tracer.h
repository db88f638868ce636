// The reference path tracer (examples/demo_renderer/shaders/path_trace.comp) as records through rhi::IDevice: uploads a
// SceneGeometry (world triangles in BVH order, materials, emitters), then adds samples per pixel to running
// sums of the AOVs, progressively. The ground truth that rasterized and GI results are measured against
// (and, through the ao AOV, the reference for voxel ambient occlusion).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bricklight/rhi.h"
#include "gpu_scene.h"
#include "scene_geometry.h"

namespace bricklight::render {

// Ao: ambient occlusion at the primary hit, the fraction of cosine-weighted hemisphere rays (about the
// shading normal, one per sample) that hit nothing within PathTracerOptions::aoRange, in all three
// channels: 1 open, 0 fully occluded; 1 where the camera ray hits nothing. Only the path tracer has it.
enum class Aov : uint32_t { Combined, Direct, IndirectDiffuse, Albedo, Normal, Depth, Ao, Count };
const char* aovName(Aov aov);               // "combined", "direct", "indirect-diffuse", ..., "ao"
bool aovFromName(const std::string& name, Aov* out);

// A linear float image, 3 channels per pixel, row 0 at the top.
struct Image {
    uint32_t width = 0, height = 0;
    std::vector<float> rgb;
    glm::vec3 at(uint32_t x, uint32_t y) const {
        const size_t i = 3 * (size_t(y) * width + x);
        return {rgb[i], rgb[i + 1], rgb[i + 2]};
    }
};

struct PathTracerOptions {
    uint32_t width = 256, height = 256;
    uint32_t maxBounces = 64;        // Russian roulette ends paths long before this
    // Per pixel and dispatch: each invocation traces this many samples in a loop. 1: on CPU drivers the
    // loop limit (samplesCutShort) is per invocation, and one sample of a deep scene may need most of it.
    uint32_t samplesPerDispatch = 1;
    uint32_t seed = 1;
    // Samples spread over the pixel (anti-aliasing). Off: every camera ray through the pixel centre, as a
    // rasterizer samples (the primary-hit AOVs then equal a G-buffer's).
    bool pixelJitter = true;
    // The ao AOV's range in world units: occluders farther than this from the primary hit do not count.
    // 0: a tenth of the diagonal of the scene's bounding box. Finite and >= 0.
    float aoRange = 0.0f;
};

class PathTracer {
public:
    // Null with `error` set for an empty scene, non-finite positions, negative albedo/emission, a camera
    // that does not make a view or an aoRange that is negative or not finite.
    static std::unique_ptr<PathTracer> create(rhi::IDevice& device, const scenes::SceneGeometry& scene,
                                              const PathTracerOptions& options, std::string* error);
    ~PathTracer();
    bool setCamera(const scenes::Camera& camera, std::string* error);  // restarts accumulation
    void addSamples(uint32_t samples);  // records dispatches; does not wait
    uint32_t samples() const { return samples_; }
    Image read(Aov aov);                // blocking; the mean of the samples so far
    // Blocking: samples that a CPU driver's loop limit cut short since the last restart (0 on GPUs): llvmpipe
    // and lavapipe end every loop of a shader invocation after 65,535 iterations of all its loops together, and
    // a sample through thousands of overlapping triangles (coincident cut-out cards) can need more. Samples not
    // finished are left out of the means; finished ones with a ray ended early are in them (the image is wrong
    // there). Callers report a count above 0 (bricklight-render warns with it).
    uint64_t samplesCutShort();
    // Samples whose radiance came out infinite or NaN: left out of the means (and of the sample counts), so the
    // image stays finite. A blocking read-back.
    uint64_t samplesNonFinite();
    uint32_t triangleCount() const { return scene_->triangleCount(); }
    float aoRange() const { return aoRange_; }  // the ao AOV's range: options.aoRange or its default

private:
    glm::dvec2 samplesLeftOut();  // summed over pixels: x cut short, y non-finite
    PathTracer(rhi::IDevice& device) : device_(device) {}
    rhi::IDevice& device_;
    PathTracerOptions options_;
    rhi::ShaderHandle shader_;
    std::unique_ptr<GpuScene> scene_;
    rhi::BufferHandle accumulation_;
    scenes::Camera camera_;
    uint32_t samples_ = 0;
    float aoRange_ = 0.0f;
};

}  // namespace bricklight::render
