// What a window can show of the renderer's latest frame: the final image, each AOV, and every SDF, GI and voxel
// cone tracing debug view (the viewer lists them; a picture-in-picture shows a second one in a corner).
#pragma once

#include <cstdint>
#include <string>

namespace bricklight::render {

enum class View : uint32_t {
    Final,  // direct + GI, as bricklight-render writes it
    Direct,
    IndirectDiffuse,
    SpecularGi,
    Albedo,
    Normal,
    Depth,
    Motion,
    SdfDistance,  // sdf::DebugMode, in its order
    SdfNormal,
    SdfIterations,
    SdfBrickId,
    SdfCascadeId,
    SdfUvw,
    GiRadianceCache,  // gi::DebugMode, in its order
    GiIrradianceCache,
    GiProbes,
    GiProbeSh,
    GiDisocclusion,
    GiSamples,
    VctOpacity,  // vct::DebugMode, in its order
    VctEmittance,
    VctLevel,
    VctRewritten,
    VctConeSamples,  // the cone tracer's samples of one pixel (RasterRenderer::setVctProbePixel)
    Reflections,     // hybrid reflections (--reflections hybrid): the denoised reflections
    ReflectionTileClass,  // reflections::ReflectionDebugMode, in its order: each 8×8 tile's class,
    ReflectionRays,       // its screen-space and SDF rays,
    ReflectionCounters,   // its hit/miss feedback counters
    Count
};

const char* viewName(View view);  // "final", "direct", ..., "sdf-normal", ..., "gi-probes", ...
bool viewFromName(const std::string& name, View* out);
bool viewNeedsGi(View view);  // the SDF, GI and VCT views and the GI AOVs exist only with GI on
bool viewIsVct(View view);    // the voxel cone tracing views (--gi vxgi); the SDF and GI views need --gi sdf
bool viewIsReflection(View view);  // the hybrid reflections' views (--reflections hybrid)

// A rectangle of the display texture, in pixels, row 0 at the top.
struct DisplayRect {
    uint32_t x = 0, y = 0, width = 0, height = 0;
};

}  // namespace bricklight::render
