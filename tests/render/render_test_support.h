// Shared by the renderer tests: the same scene through both paths, rendered once (the fast path with
// `lightSamples` per pixel, the path tracer with `spp`; `jitter` off puts camera rays at pixel centres, as
// the rasterizer samples).
#pragma once

#include <memory>

#include "backend_test.h"
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

}  // namespace bricklight::testing
