// Shared by the renderer tests: the same scene through both paths, rendered once (the fast path with
// `lightSamples` per pixel, the path tracer with `spp`; `jitter` off puts camera rays at pixel centres, as
// the rasterizer samples).
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "backend_test.h"
#include "image_metrics.h"
#include "path_tracer.h"
#include "raster_renderer.h"

namespace bricklight::testing {

struct Pair {
    std::unique_ptr<render::RasterRenderer> raster;
    std::unique_ptr<render::PathTracer> tracer;
};

inline Pair makePair(TestDevice& td, const scenes::SceneGeometry& scene, uint32_t size, uint32_t lightSamples, uint32_t spp,
                     bool jitter = true) {
    std::string error;
    render::RasterOptions ro;
    ro.width = ro.height = size;
    ro.lightSamples = lightSamples;
    Pair p;
    p.raster = render::RasterRenderer::create(*td.device, scene, ro, &error);
    INFO(error);
    REQUIRE(p.raster);
    render::PathTracerOptions po;
    po.width = po.height = size;
    po.pixelJitter = jitter;
    p.tracer = render::PathTracer::create(*td.device, scene, po, &error);
    REQUIRE(p.tracer);
    p.raster->render();
    p.tracer->addSamples(spp);
    return p;
}

// The path tracer alone: `spp` samples per pixel added (not read yet).
inline std::unique_ptr<render::PathTracer> traced(TestDevice& td, const scenes::SceneGeometry& scene, uint32_t size, uint32_t spp,
                                                  bool jitter = true, uint32_t seed = 1,
                                                  uint32_t maxBounces = render::PathTracerOptions{}.maxBounces) {
    render::PathTracerOptions o;
    o.width = o.height = size;
    o.pixelJitter = jitter;
    o.seed = seed;
    o.maxBounces = maxBounces;
    std::string error;
    auto pt = render::PathTracer::create(*td.device, scene, o, &error);
    INFO(error);
    REQUIRE(pt);
    pt->addSamples(spp);
    return pt;
}

// n frames of the fast path, each ended on the device.
inline void frames(TestDevice& td, render::RasterRenderer& r, uint32_t n) {
    for (uint32_t f = 0; f < n; ++f) {
        r.render();
        td.device->endFrame();
    }
}

// The mean of every channel of every pixel.
inline double imageMean(const render::Image& img) {
    double s = 0.0;
    for (float v : img.rgb) s += v;
    return img.rgb.empty() ? 0.0 : s / double(img.rgb.size());
}

inline bool allFinite(const std::vector<float>& v) {
    for (float x : v)
        if (!std::isfinite(x)) return false;
    return true;
}

// How close an image must come to a path-traced reference: relMSE below, SSIM above, its mean within
// [minMean, maxMean] × the reference's. Only the bounds given are checked.
struct ReferenceBounds {
    std::optional<double> relMse, ssim, minMean, maxMean;
};

// The comparison of `image` with `reference` that the technique tests share: the metrics (named `what` in the
// report) and the checks of `bounds`.
inline render::ImageMetrics checkAgainstReference(const std::string& what, const render::Image& image, const render::Image& reference,
                                                  const ReferenceBounds& bounds) {
    const render::ImageMetrics m = render::compareImages(image, reference);
    INFO(what << " relMSE " << m.relMse << " SSIM " << m.ssim << " mean " << m.meanA << " vs " << m.meanB);
    if (bounds.relMse) CHECK(m.relMse < *bounds.relMse);
    if (bounds.ssim) CHECK(m.ssim > *bounds.ssim);
    if (bounds.minMean) CHECK(m.meanA > *bounds.minMean * m.meanB);
    if (bounds.maxMean) CHECK(m.meanA < *bounds.maxMean * m.meanB);
    return m;
}

// GI's inputs from the renderer's G-buffer (the renderer's own GI takes the same), into the given outputs.
inline gi::DispatchDesc giInputsOf(const render::GBufferView& g, rhi::TextureHandle outputDiffuse, rhi::TextureHandle outputSpecular) {
    gi::DispatchDesc d;
    d.camera.view = g.view;
    d.camera.projection = g.projection;
    d.camera.previousView = g.previousView;
    d.camera.previousProjection = g.previousProjection;
    d.cameraPosition = g.eye;
    d.gbuffer.depth = g.depth;
    d.gbuffer.normals = g.normal;
    d.gbuffer.normalsUnpackScale = glm::vec3(1.0f);
    d.gbuffer.normalsUnpackOffset = glm::vec3(0.0f);
    d.gbuffer.roughness = g.albedo;
    d.gbuffer.roughnessChannel = 3;
    d.gbuffer.motionVectors = g.motion;
    d.previousLitOutput = g.lit;
    d.outputDiffuse = outputDiffuse;
    d.outputSpecular = outputSpecular;
    return d;
}

// A square in the y = 0 plane, `half` wide each way, facing +y (counter-clockwise seen from above).
inline scenes::TriangleMesh groundPlane(float half, glm::vec3 albedo) {
    scenes::TriangleMesh plane;
    plane.name = "plane";
    plane.positions = {-half, 0, -half, half, 0, -half, half, 0, half, -half, 0, half};
    plane.indices = {0, 2, 1, 0, 3, 2};
    plane.albedo = albedo;
    return plane;
}

// A closed sphere seen from inside (radius 1): albedo rho, every surface emitting radiance `emission` towards
// the inside. Its light is known in closed form: after n bounces L = emission · Σ_{k ≤ n} rhoᵏ, converged
// emission / (1 − rho), the same everywhere. 20 × 4^subdivisions triangles.
inline scenes::SceneGeometry emittingSphere(float rho, float emission, uint32_t subdivisions = 3) {
    scenes::SceneGeometry s;
    scenes::TriangleMesh sphere = scenes::icosphere(subdivisions);
    for (size_t i = 0; i < sphere.indices.size(); i += 3) std::swap(sphere.indices[i + 1], sphere.indices[i + 2]);  // face inwards
    sphere.albedo = glm::vec3(rho);
    sphere.emission = glm::vec3(emission);
    s.meshes.push_back(sphere);
    s.instances.push_back({0, glm::mat4(1.0f)});
    s.camera = {glm::vec3(0.1f, -0.2f, 0.3f), glm::vec3(0.5f, 0.2f, -1.0f), glm::vec3(0, 1, 0), 90.0f};
    s.computeBounds();
    return s;
}

// A fast-path renderer of `scene` at size² with the SDF GI, its other options the defaults.
inline std::unique_ptr<render::RasterRenderer> sdfGiRenderer(TestDevice& td, const scenes::SceneGeometry& scene, uint32_t size) {
    render::RasterOptions o;
    o.width = o.height = size;
    o.gi = true;
    std::string error;
    auto r = render::RasterRenderer::create(*td.device, scene, o, &error);
    INFO(error);
    REQUIRE(r);
    return r;
}

// The mean indirect-diffuse light of a fast-path renderer of `scene` with options `o` after `frameCount` frames, every
// pixel finite: the closed-form tests' measure (emittingSphere).
inline double indirectMeanAfter(TestDevice& td, const scenes::SceneGeometry& scene, const render::RasterOptions& o, uint32_t frameCount) {
    std::string error;
    auto r = render::RasterRenderer::create(*td.device, scene, o, &error);
    INFO(error);
    REQUIRE(r);
    frames(td, *r, frameCount);
    const render::Image indirect = r->read(render::Aov::IndirectDiffuse);
    REQUIRE(allFinite(indirect.rgb));
    return imageMean(indirect);
}

// A white furnace: `mesh` alone at the origin under a uniform sky of radiance 1, seen from 4 units away.
inline scenes::SceneGeometry furnace(const scenes::TriangleMesh& mesh) {
    scenes::SceneGeometry s;
    s.meshes.push_back(mesh);
    s.instances.push_back({0, glm::mat4(1.0f)});
    s.environment.skyRadiance = glm::vec3(1.0f);
    s.camera = {glm::vec3(0, 0, 4), glm::vec3(0), glm::vec3(0, 1, 0), 30.0f};
    s.computeBounds();
    return s;
}

}  // namespace bricklight::testing
