// bricklight-viewer's application: the scene, the renderer (examples/demo_renderer, the same one bricklight-render
// drives, through the same options and frame loop), the camera, the panels and the frame loop on a
// ViewerBackend's window.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "camera_bookmarks.h"
#include "fly_camera.h"
#include "frame_stats.h"
#include "raster_renderer.h"
#include "render_options.h"
#include "viewer_backend.h"

namespace bricklight::viewer {

// Everything the command line sets (docs/viewer.md).
struct ViewerSettings {
    render::RenderOptions render;  // the options bricklight-render shares (scene, backend, GI, ...)
    bool fixedSize = false;        // --width/--height given: render at that size, scaled to the window
    uint32_t windowWidth = 960, windowHeight = 540;
    uint32_t exitAfterFrames = 0;  // --frames N with --screenshot, or --exit-after N: quit after N frames
    std::string screenshot;        // written after the last frame (--screenshot FILE)
    std::string screenshotDir = ".";  // where the screenshot key writes bricklight-viewer-N.png
    bool vsync = true;
    uint32_t fpsLimit = 0;  // 0: none
    render::View view = render::View::Final;
    bool pip = false;
    render::View pipView = render::View::IndirectDiffuse;
    bool hidden = false;
    bool log = false;
    bool openPanels = false;  // --open-panels: every panel section open  // --log: one line per state change and screenshot on stdout (tests follow it)
};

// What the panels change in the scene's light (applied to a copy of the scene as loaded).
struct LightSettings {
    float sunAzimuthDegrees = 0.0f, sunElevationDegrees = 45.0f;
    float sunIrradiance = 0.0f;  // on a surface facing the sun
    glm::vec3 sunColor{1.0f};
    bool emitters = true;
    bool pointLights = true;
};

// GI and SDF parameters; the live ones reach the renderer each frame, the others rebuild it.
struct GiSettings {
    gi::TraceParams trace;
    float roughnessThreshold = 0.75f;
    uint32_t injectTile = 0, probeTile = 0, cacheBricks = 0;  // 0: automatic
    bool relight = true;
    uint32_t sdfCascades = 3;
    sdf::Budgets sdfBudgets;
    glm::vec3 sdfCenterOffset{0.0f};  // the cascades' centre from the scene's centre (live)
    // Voxel cone tracing (--gi vxgi, --ao vxao): the clip-map (rebuild) and the tracing (live).
    uint32_t vctResolution = 64, vctLevels = 5;
    vct::EmittanceMode vctEmittance = vct::EmittanceMode::Anisotropic;
    vct::ConeTraceParams vctTrace;
    int vctProbePixel[2] = {-1, -1};  // the vct-cone-samples view's pixel (−1: the image's centre)
};

class ViewerApp {
public:
    // The whole program after argument parsing: 0 done, 1 failed (a message on stderr).
    static int run(const ViewerSettings& settings);

    // For panels and techniques.
    ViewerSettings& settings() { return settings_; }
    LightSettings& lights() { return lights_; }
    GiSettings& gi() { return gi_; }
    render::RasterRenderer* renderer() { return renderer_.get(); }
    ViewerBackend& backend() { return *backend_; }
    FrameStats& stats() { return stats_; }
    const scenes::SceneGeometry& scene() const { return scene_; }
    // Recreate the renderer before the next frame (an option that is fixed at creation changed).
    void requestRebuild() { rebuild_ = true; }
    // Hand the scene, with the light settings applied, to the renderer before the next frame.
    void requestLightUpdate() { lightsChanged_ = true; }
    void setView(render::View view);
    void setGiEnabled(bool on);
    void requestScreenshot() { screenshotRequested_ = true; }
    void log(const std::string& line);  // stdout with --log; also the panel's message list
    const std::vector<std::string>& messages() const { return messages_; }

private:
    explicit ViewerApp(const ViewerSettings& settings) : settings_(settings) {}
    bool start(std::string* error);
    bool frame(std::string* error);  // one frame; false on a failure that ends the run
    bool renderFrame(bool stepAnimation, std::string* error);  // inside a begun frame
    bool buildRenderer(std::string* error);
    // A rebuild the library refused (a panel's setting it does not take) goes back to the last settings
    // that built; false only if those fail too.
    bool rebuildOrRestore(std::string* error);
    void applyLights(bool upload);
    void report(rhi::Severity severity, const std::string& message);  // every layer's messages
    void handleKey(int key, int mods);
    void cameraInput(float seconds);
    bool writeScreenshot(const std::string& path, std::string* error);
    void drawPanels();
    static void keyCallback(GLFWwindow* window, int key, int scancode, int action, int mods);

    ViewerSettings settings_;
    LightSettings lights_;
    GiSettings gi_;
    render::RenderOptions builtOptions_;  // what the current renderer was built with (rebuildOrRestore)
    GiSettings builtGi_;
    std::unique_ptr<ViewerBackend> backend_;
    scenes::SceneGeometry loaded_, scene_;  // as loaded; with the light settings and the animation applied
    std::unique_ptr<render::RasterRenderer> renderer_;
    FlyCamera camera_;
    std::vector<CameraBookmark> bookmarks_;
    bool cameraMoved_ = false;
    FrameStats stats_;
    uint32_t renderWidth_ = 0, renderHeight_ = 0;
    uint32_t animationFrame_ = 0;  // the scene's frame: advances while playing
    uint64_t framesRendered_ = 0;
    bool playing_ = true;
    bool rebuild_ = false, lightsChanged_ = false, screenshotRequested_ = false, showUi_ = true;
    uint32_t screenshotCount_ = 0;
    std::vector<int> keys_;  // pressed since the last frame (from the key callback: no press is lost)
    void (*previousKeyCallback_)(GLFWwindow*, int, int, int, int) = nullptr;
    double lastFrameSeconds_ = -1.0;  // glfwGetTime() at the previous frame
    uint64_t errors_ = 0;
    std::string firstError_;
    std::vector<std::string> messages_;
};

}  // namespace bricklight::viewer
