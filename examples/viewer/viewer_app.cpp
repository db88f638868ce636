#include "viewer_app.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "image_io.h"
#include "output_file.h"

namespace bricklight::viewer {

namespace {

float sceneSize(const scenes::SceneGeometry& scene) { return glm::length(scene.boundsMax - scene.boundsMin); }

// The keys the viewer reacts to (docs/viewer.md, "Controls").
constexpr int kToggleGi = GLFW_KEY_G, kNextView = GLFW_KEY_V, kPreviousView = GLFW_KEY_B, kTogglePip = GLFW_KEY_P,
              kScreenshot = GLFW_KEY_F12, kToggleUi = GLFW_KEY_F1, kPause = GLFW_KEY_SPACE, kOrbit = GLFW_KEY_TAB;

}  // namespace

int ViewerApp::run(const ViewerSettings& settings) {
    ViewerApp app(settings);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to wherever the viewer was started
    std::string error;
    int status = 0;
    if (!app.start(&error)) {
        std::fprintf(stderr, "bricklight-viewer: %s\n", error.c_str());
        status = 1;
    } else {
        using Clock = std::chrono::steady_clock;
        while (!glfwWindowShouldClose(app.backend_->window())) {
            const Clock::time_point begin = Clock::now();
            if (!app.frame(&error)) {
                std::fprintf(stderr, "bricklight-viewer: %s\n", error.c_str());
                status = 1;
                break;
            }
            if (settings.exitAfterFrames && app.framesRendered_ >= settings.exitAfterFrames) break;
            if (app.settings_.fpsLimit) {  // the frame limiter: sleep off what is left of the frame's time
                const auto period = std::chrono::duration<double>(1.0 / app.settings_.fpsLimit);
                std::this_thread::sleep_until(begin + std::chrono::duration_cast<Clock::duration>(period));
            }
        }
        const std::vector<float>& gpu = app.stats_.gpuFrameHistory();
        float gpuMean = 0.0f;
        for (float v : gpu) gpuMean += v / float(gpu.size());
        char line[160];
        std::snprintf(line, sizeof line, "frame time: %.2f ms (CPU, mean of the last %zu frames), GPU %.2f ms, %ux%u",
                      app.stats_.averageCpuMilliseconds(), app.stats_.cpuFrameHistory().size(), gpuMean, app.renderWidth_,
                      app.renderHeight_);
        app.log(line);
        // Errors first: a frame they spoiled is not written (as bricklight-render writes nothing then).
        if (status == 0 && app.errors_ && settings.exitAfterFrames) {
            std::fprintf(stderr, "bricklight-viewer: %llu error(s) were reported (the first: %s)%s\n",
                         static_cast<unsigned long long>(app.errors_), app.firstError_.c_str(),
                         settings.screenshot.empty() ? "" : "; no screenshot written");
            status = 1;
        }
        if (status == 0 && !settings.screenshot.empty()) {
            if (!app.writeScreenshot(settings.screenshot, &error)) {
                std::fprintf(stderr, "bricklight-viewer: %s\n", error.c_str());
                status = 1;
            }
        }
    }
    if (app.backend_) app.backend_->waitIdle();
    app.renderer_.reset();  // its resources go before the device
    app.backend_.reset();
    ImGui::DestroyContext();
    return status;
}

bool ViewerApp::start(std::string* error) {
    // Outputs first: a bad path costs no window and no render.
    if (!settings_.screenshot.empty() && !render::checkOutputPath(settings_.screenshot, error)) return false;
    // The screenshot key's folder: a file or a missing folder would only show when the key is pressed.
    if (!render::checkOutputPath(settings_.screenshotDir + "/bricklight-viewer-1.png", error)) {
        *error = "--screenshot-dir '" + settings_.screenshotDir + "': " + *error;
        return false;
    }
    loaded_ = render::loadSceneOf(settings_.render, error);
    if (loaded_.meshes.empty()) return false;
    for (const std::string& w : loaded_.warnings) log("warning: " + w);
    scene_ = loaded_;
    // The panels start from the scene's own sun.
    const glm::vec3 sun = loaded_.environment.sunIrradiance;
    const float peak = std::max(sun.x, std::max(sun.y, sun.z));
    lights_.sunIrradiance = peak;
    lights_.sunColor = peak > 0.0f ? sun / peak : glm::vec3(1.0f);
    const glm::vec3 d = glm::normalize(loaded_.environment.sunDirection);
    lights_.sunElevationDegrees = glm::degrees(std::asin(std::clamp(d.y, -1.0f, 1.0f)));
    lights_.sunAzimuthDegrees = glm::degrees(std::atan2(d.x, d.z));
    camera_.reset(loaded_.camera, sceneSize(loaded_));
    bookmarks_ = cameraBookmarks(settings_.render.scene, loaded_);
    const render::RasterOptions defaults;
    gi_.trace = defaults.giTrace;
    gi_.roughnessThreshold = defaults.giRoughnessThreshold;
    gi_.sdfCascades = defaults.sdfCascades;
    gi_.sdfBudgets = defaults.sdfBudgets;

    BackendOptions bo;
    bo.width = settings_.windowWidth;
    bo.height = settings_.windowHeight;
    bo.vsync = settings_.vsync;
    bo.validation = settings_.render.validate;
    bo.hidden = settings_.hidden;
    bo.title = "bricklight-viewer: " + loaded_.name + " (" + settings_.render.backend + ")";
    bo.errorCallback = [this](rhi::Severity s, const std::string& m) { report(s, m); };
    backend_ = settings_.render.backend == "gl" ? ViewerBackend::createGl(bo, error) : ViewerBackend::createVulkan(bo, error);
    if (!backend_) return false;
    backend_->device().setTimingEnabled(true);
    // Our key handler runs after ImGui's (installed by the backend), which it forwards to.
    previousKeyCallback_ = glfwSetKeyCallback(backend_->window(), keyCallback);
    glfwSetWindowUserPointer(backend_->window(), this);
    return buildRenderer(error);
}

bool ViewerApp::buildRenderer(std::string* error) {
    rebuild_ = false;
    backend_->waitIdle();
    renderer_.reset();
    uint32_t w = settings_.render.width, h = settings_.render.height;
    if (!settings_.fixedSize) {  // the window's size
        int fw = 0, fh = 0;
        glfwGetFramebufferSize(backend_->window(), &fw, &fh);
        w = uint32_t(std::max(fw, 1));
        h = uint32_t(std::max(fh, 1));
    }
    render::RenderOptions options = settings_.render;
    options.width = w;
    options.height = h;
    render::RasterOptions ro = render::rasterOptionsOf(options);
    ro.giTrace = gi_.trace;
    ro.giRoughnessThreshold = gi_.roughnessThreshold;
    ro.giInjectTile = gi_.injectTile;
    ro.giProbeTile = gi_.probeTile;
    ro.giCacheBricks = gi_.cacheBricks;
    ro.giRelight = gi_.relight;
    ro.sdfCascades = gi_.sdfCascades;
    ro.sdfBudgets = gi_.sdfBudgets;
    ro.vctResolution = gi_.vctResolution;
    ro.vctLevels = gi_.vctLevels;
    ro.vctEmittance = gi_.vctEmittance;
    ro.vctTrace = gi_.vctTrace;
    ro.errorCallback = [this](rhi::Severity s, const std::string& m) { report(s, m); };
    renderer_ = render::RasterRenderer::create(backend_->device(), scene_, ro, error);
    if (!renderer_) return false;
    builtOptions_ = settings_.render;
    builtGi_ = gi_;
    renderWidth_ = w;
    renderHeight_ = h;
    cameraMoved_ = camera_.camera().eye != scene_.camera.eye || camera_.camera().at != scene_.camera.at;
    log("renderer " + std::to_string(w) + "x" + std::to_string(h) + (settings_.render.gi ? ", GI on" : ", GI off"));
    return true;
}

// Every message of the device, the validation layers and our passes: on stderr and in the panel, and
// counted: a --frames run with an error fails, as bricklight-render's does.
void ViewerApp::report(rhi::Severity s, const std::string& m) {
    if (s == rhi::Severity::Info) return;
    std::fprintf(stderr, "bricklight-viewer: %s%s\n", s == rhi::Severity::Warning ? "warning: " : "", m.c_str());
    if (s == rhi::Severity::Error && errors_++ == 0) firstError_ = m;
    messages_.push_back(m);
    if (messages_.size() > 64) messages_.erase(messages_.begin());
}

bool ViewerApp::rebuildOrRestore(std::string* error) {
    if (buildRenderer(error)) return true;
    log("the change was refused: " + *error + "; back to the previous settings");
    settings_.render = builtOptions_;
    gi_ = builtGi_;
    return buildRenderer(error);
}

// The light settings applied to the scene; `upload` hands it to the renderer (an animation step about to
// call setScene this frame does that itself: two calls would leave the frame without motion).
void ViewerApp::applyLights(bool upload) {
    lightsChanged_ = false;
    const float az = glm::radians(lights_.sunAzimuthDegrees), el = glm::radians(lights_.sunElevationDegrees);
    scene_.environment.sunDirection = glm::vec3(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
    scene_.environment.sunIrradiance = lights_.sunColor * lights_.sunIrradiance;
    for (size_t i = 0; i < scene_.meshes.size(); ++i) scene_.meshes[i].emission = lights_.emitters ? loaded_.meshes[i].emission : glm::vec3(0.0f);
    for (size_t i = 0; i < scene_.pointLights.size(); ++i)
        scene_.pointLights[i].intensity = lights_.pointLights ? loaded_.pointLights[i].intensity : glm::vec3(0.0f);
    std::string error;
    if (upload && !renderer_->setScene(scene_, &error)) log("the light change was refused: " + error);
}

void ViewerApp::keyCallback(GLFWwindow* window, int key, int scancode, int action, int mods) {
    auto* app = static_cast<ViewerApp*>(glfwGetWindowUserPointer(window));
    if (app->previousKeyCallback_) app->previousKeyCallback_(window, key, scancode, action, mods);
    if (action == GLFW_PRESS && !ImGui::GetIO().WantCaptureKeyboard) app->keys_.push_back(key | mods << 16);
}

void ViewerApp::setView(render::View view) {
    if (render::viewNeedsGi(view) && !settings_.render.gi) {
        log(std::string("view ") + render::viewName(view) + " needs GI");
        return;
    }
    settings_.view = view;
    log(std::string("view: ") + render::viewName(view));
}

void ViewerApp::setGiEnabled(bool on) {
    if (settings_.render.gi == on) return;
    settings_.render.gi = on;
    if (!on && render::viewNeedsGi(settings_.view)) settings_.view = render::View::Final;
    if (!on && render::viewNeedsGi(settings_.pipView)) settings_.pip = false;
    rebuild_ = true;
    log(std::string("gi: ") + (on ? "on" : "off"));
}

void ViewerApp::handleKey(int key, int mods) {
    const uint32_t viewCount = uint32_t(render::View::Count);
    auto step = [&](int direction) {  // the next view that exists with the current settings
        uint32_t v = uint32_t(settings_.view);
        for (uint32_t k = 0; k < viewCount; ++k) {
            v = (v + viewCount + uint32_t(direction)) % viewCount;
            if (!render::viewNeedsGi(render::View(v)) || settings_.render.gi) break;
        }
        setView(render::View(v));
    };
    if (key == kToggleGi) setGiEnabled(!settings_.render.gi);
    else if (key == kNextView) step(+1);
    else if (key == kPreviousView) step(-1);
    else if (key == kTogglePip) {
        settings_.pip = !settings_.pip && (settings_.render.gi || !render::viewNeedsGi(settings_.pipView));
        log(std::string("pip: ") + (settings_.pip ? render::viewName(settings_.pipView) : "off"));
    } else if (key == kScreenshot) requestScreenshot();
    else if (key == kToggleUi) showUi_ = !showUi_;
    else if (key == kPause) {
        playing_ = !playing_;
        log(playing_ ? "animation: playing" : "animation: paused");
    } else if (key == kOrbit) {
        camera_.setMode(camera_.mode() == FlyCamera::Mode::Fly ? FlyCamera::Mode::Orbit : FlyCamera::Mode::Fly);
        log(camera_.mode() == FlyCamera::Mode::Orbit ? "camera: orbit" : "camera: fly");
    } else if (key >= GLFW_KEY_1 && key < GLFW_KEY_1 + int(bookmarks_.size())) {
        const CameraBookmark& b = bookmarks_[size_t(key - GLFW_KEY_1)];
        camera_.reset(b.camera, sceneSize(loaded_));
        cameraMoved_ = true;
        renderer_->cameraCut();  // a jump: GI must not reproject its history across it
        log("camera: " + b.name);
    } else if (key == GLFW_KEY_ESCAPE) {
        glfwSetWindowShouldClose(backend_->window(), GLFW_TRUE);
    }
    (void)mods;
}

void ViewerApp::cameraInput(float seconds) {
    GLFWwindow* w = backend_->window();
    const ImGuiIO& io = ImGui::GetIO();
    CameraInput in;
    in.seconds = seconds;
    if (!io.WantCaptureKeyboard) {
        auto axis = [&](int plus, int minus) {
            return float(glfwGetKey(w, plus) == GLFW_PRESS) - float(glfwGetKey(w, minus) == GLFW_PRESS);
        };
        in.move = {axis(GLFW_KEY_D, GLFW_KEY_A), axis(GLFW_KEY_E, GLFW_KEY_Q), axis(GLFW_KEY_W, GLFW_KEY_S)};
        in.fast = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
    }
    if (!io.WantCaptureMouse) {
        // Look with the right button held (the left one is the panels'), or any button in orbit mode.
        const bool looking = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                             (camera_.mode() == FlyCamera::Mode::Orbit && glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS);
        if (looking) in.look = {io.MouseDelta.x, io.MouseDelta.y};
        in.scroll = io.MouseWheel;
    }
    if (camera_.update(in)) cameraMoved_ = true;
}

bool ViewerApp::frame(std::string* error) {
    const double now = glfwGetTime();
    const float seconds = lastFrameSeconds_ < 0.0 ? 0.0f : float(now - lastFrameSeconds_);
    lastFrameSeconds_ = now;
    glfwPollEvents();
    // Changes that recreate the renderer happen between frames (no command buffer is being recorded).
    if (!settings_.fixedSize) {
        int fw = 0, fh = 0;
        glfwGetFramebufferSize(backend_->window(), &fw, &fh);
        if (fw > 0 && fh > 0 && (uint32_t(fw) != renderWidth_ || uint32_t(fh) != renderHeight_)) rebuild_ = true;
    }
    if (rebuild_ && !rebuildOrRestore(error)) return false;
    const bool stepAnimation = playing_ && framesRendered_ > 0 && scene_.animate;
    if (lightsChanged_) applyLights(!stepAnimation);
    if (!backend_->beginFrame()) {
        if (backend_->failed()) return *error = "the window cannot show frames any more (see the message above)", false;
        glfwWaitEventsTimeout(0.1);  // minimized: nothing to draw
        return true;
    }
    ImGui::NewFrame();
    for (int k : keys_) handleKey(k & 0xFFFF, k >> 16);
    keys_.clear();
    cameraInput(seconds);
    // Once a frame has begun it is always ended (the embedded device records into its command buffer until
    // endFrame hands it back); a failure inside is returned after that.
    const bool ok = renderFrame(stepAnimation, error);
    if (ok && showUi_) drawPanels();
    ImGui::Render();
    backend_->endFrame(ImGui::GetDrawData());
    if (!ok) return false;
    ++framesRendered_;
    stats_.update(backend_->device(), seconds * 1000.0f);
    if (framesRendered_ == 1) log("first frame");
    if (screenshotRequested_) {
        screenshotRequested_ = false;
        const std::string path = settings_.screenshotDir + "/bricklight-viewer-" + std::to_string(++screenshotCount_) + ".png";
        std::string why;
        if (!writeScreenshot(path, &why)) log("screenshot failed: " + why);
    }
    return !backend_->failed() || (*error = "the window cannot show frames any more (see the message above)", false);
}

// The frame loop bricklight-render runs (render_options.h): the scene's frame, then the render; then the
// picture: the view fitted into the window (letterboxed when the render size is fixed), and the
// picture-in-picture in the lower right corner.
bool ViewerApp::renderFrame(bool stepAnimation, std::string* error) {
    if (stepAnimation) {
        ++animationFrame_;
        if (!render::animateTo(scene_, *renderer_, animationFrame_, error)) return false;
    }
    if (cameraMoved_) {  // untouched, the renderer keeps the scene's camera exactly as bricklight-render does
        if (!renderer_->setCamera(camera_.camera(), error)) return false;
        cameraMoved_ = false;
    }
    renderer_->setGiTuning(gi_.trace, gi_.roughnessThreshold);
    renderer_->setVctTuning(gi_.vctTrace);
    renderer_->setSdfCenter(renderer_->sceneCenter() + gi_.sdfCenterOffset);
    renderer_->render();
    const uint32_t dw = backend_->displayWidth(), dh = backend_->displayHeight();
    render::DisplayRect full{0, 0, dw, dh};
    if (settings_.fixedSize) {
        const double scale = std::min(double(dw) / renderWidth_, double(dh) / renderHeight_);
        full.width = std::max(1u, uint32_t(renderWidth_ * scale));
        full.height = std::max(1u, uint32_t(renderHeight_ * scale));
        full.x = (dw - full.width) / 2;
        full.y = (dh - full.height) / 2;
        if (full.width != dw || full.height != dh) backend_->device().clearTexture(backend_->displayTexture(), 0, 1, rhi::ClearValue{});
    }
    std::string why;
    if (!renderer_->drawView(settings_.view, backend_->displayTexture(), full, settings_.render.exposure, &why)) log(why);
    if (settings_.pip && full.width >= 24 && full.height >= 24) {  // a third of the picture, 8 pixels in
        const render::DisplayRect pip{full.x + full.width - full.width / 3 - 8, full.y + full.height - full.height / 3 - 8,
                                      full.width / 3, full.height / 3};
        if (!renderer_->drawView(settings_.pipView, backend_->displayTexture(), pip, settings_.render.exposure, &why)) log(why);
    }
    return true;
}

// The current view at the render size, through the display pass into a texture of our own (no UI, no
// picture-in-picture), read back between frames and written as a PNG: for the final view the bytes
// bricklight-render's PNG has for the same frame, up to the GPU's rounding.
bool ViewerApp::writeScreenshot(const std::string& path, std::string* error) {
    rhi::IDevice& device = backend_->device();
    rhi::TextureDesc d;
    d.format = rhi::Format::RGBA8_UNORM;
    d.width = renderWidth_;
    d.height = renderHeight_;
    d.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    d.debugName = "screenshot";
    const rhi::TextureHandle t = device.createTexture(d);
    if (!t) return *error = "cannot create the screenshot texture", false;
    std::vector<uint8_t> bytes(size_t(d.width) * d.height * 4);
    bool ok = renderer_->drawView(settings_.view, t, {0, 0, d.width, d.height}, settings_.render.exposure, error) &&
              device.readTexture(t, {}, bytes.data());
    device.destroy(t);
    if (!ok) return error->empty() ? (*error = "reading the screenshot back failed", false) : false;
    if (!render::writeDisplayImage(path, d.width, d.height, bytes, error)) return false;
    log("screenshot " + path + " (" + render::viewName(settings_.view) + ", frame " + std::to_string(framesRendered_) + ")");
    return true;
}

void ViewerApp::log(const std::string& line) {
    if (settings_.log) {
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
    }
    messages_.push_back(line);
    if (messages_.size() > 64) messages_.erase(messages_.begin());
}

}  // namespace bricklight::viewer
