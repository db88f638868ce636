// The options both front ends take (bricklight-render and bricklight-viewer): the scene, the camera, the
// backend, the size, the techniques and their parameters, and the limits on model files. One parser and one
// frame loop, so that the same command line gives the same picture in both programs.
#pragma once

#include <cstdint>
#include <string>

#include "bricklight/gi.h"
#include "load_limits.h"
#include "raster_renderer.h"
#include "scene_geometry.h"

namespace bricklight::render {

struct RenderOptions {
    std::string scene = "cornell";  // a built-in scene's name or a model file
    std::string backend = "vulkan";
    uint32_t width = 256, height = 256;
    uint32_t frames = 1;
    bool framesGiven = false;  // without --frames a still image with GI gets kDefaultGiFrames
    bool haveCamera = false;
    float camera[6] = {};  // eye, at
    float exposure = 1.0f;
    bool gi = true;
    GiTechnique giTechnique = GiTechnique::Sdf;  // --gi sdf|vxgi|none
    bool vxao = false;                            // --ao vxao
    bool vctSdfOcclusion = false;                 // --vct-occlusion sdf (RasterOptions::vctSdfOcclusion)
    bool giUnseenFromVct = false;                 // --gi-unseen vxgi (RasterOptions::giUnseenFromVct)
    bool giUnseenPath = false;                    // --gi-unseen path (RasterOptions::giUnseenPath)
    float vctVoxel = 0.0f;                        // --vct-voxel (RasterOptions::vctFinestVoxel; 0: the scene's)
    gi::InternalResolution giScale = gi::InternalResolution::Native;
    ShadowMode shadows = ShadowMode::Bvh;         // --shadows bvh|shadowmap|hybrid (RasterOptions::shadows)
    ReflectionMode reflections = ReflectionMode::Gi;  // --reflections gi|hybrid (RasterOptions::reflections)
    FoliageMode foliage = FoliageMode::AlphaAware;    // --foliage alpha-aware|opaque|left-out (RasterOptions::foliage)
    SunShadowOptions sunShadows;                  // --shadow-resolution, --shadow-lambda, --shadow-pcf
    float sunAngleDegrees = -1.0f;                // --sun-angle: the scene's sun's angular diameter (< 0: the scene's own)
    bool singleBounce = false;
    bool validate = false;      // every call through rhi::createValidationDevice
    scenes::LoadLimits limits;  // what a model file may cost (docs/render.md, "Untrusted files")
};

// GI converges over frames (each frame's light feeds the next): a still image gets this many by default.
constexpr uint32_t kDefaultGiFrames = 64;

enum class OptionParse { Consumed, NotShared, Error };

// If argv[i] is one of the shared options, reads it (and its value, advancing i) into `options`. Numbers are
// read as numbers: digits only, range-checked, no wrap-around. On Error, *error says what is wrong.
OptionParse parseSharedOption(int argc, char** argv, int& i, RenderOptions& options, std::string* error);
// A whole number in lo..hi, read as a number: digits only (no sign, so "-18446744073709551615" cannot wrap
// around), no overflow. False with *error naming the option otherwise.
bool parseWholeNumber(const char* text, const std::string& option, uint32_t lo, uint32_t hi, uint32_t* out,
                      std::string* error);
// Checks across options after parsing (the backend's name); false with *error on a bad combination.
bool checkSharedOptions(const RenderOptions& options, std::string* error);
// The usage lines of the shared options.
const char* sharedOptionsUsage();

// The scene the options name, with --camera applied; empty meshes and *error on failure.
scenes::SceneGeometry loadSceneOf(const RenderOptions& options, std::string* error);
// The fast path's settings for these options.
RasterOptions rasterOptionsOf(const RenderOptions& options);
// How many frames the fast path renders for these options and this scene.
uint32_t framesToRender(const RenderOptions& options, const scenes::SceneGeometry& scene);

// Moves an animated scene to frame `frame` (> 0) and hands it to the renderer; frame 0 is the scene as
// loaded. Does nothing for a still scene. False with *error if the renderer refuses the new state.
bool animateTo(scenes::SceneGeometry& scene, RasterRenderer& renderer, uint32_t frame, std::string* error);

}  // namespace bricklight::render
