// bricklight-viewer-backend-smoke [--backend vulkan|gl] [--frames N] [--out FILE.ppm] [--hidden]
// Opens the viewer's window on one backend with validation on and renders N frames with an ImGui window
// on top. The first half clears the display texture to a known colour (clearTexture); then the window is
// resized and the second half uploads the same colour with a red band over the top rows (writeTexture), so
// a look at the window shows whether row 0 is at the top. The display texture is read back between frames
// and checked. Exit 0 and "ok" only if every check passed and the device and the validation layer said
// nothing.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "viewer_backend.h"

namespace {

using namespace bricklight;

int fail(const std::string& message) {
    std::fprintf(stderr, "bricklight-viewer-backend-smoke: %s\n", message.c_str());
    return 1;
}

constexpr uint32_t kBandRows = 8;
constexpr uint8_t kBand[4] = {255, 0, 0, 255};

// The clear colour {0.25, 0.5, 0.75, 1} in UNORM8, the top `bandRows` rows red; +-1 for rounding.
bool checkDisplay(viewer::ViewerBackend& backend, const char* when, uint32_t bandRows, std::vector<uint8_t>* pixels,
                  std::string* error) {
    const uint32_t w = backend.displayWidth(), h = backend.displayHeight();
    pixels->assign(size_t(w) * h * 4, 0);
    if (!backend.device().readTexture(backend.displayTexture(), {}, pixels->data()))
        return *error = std::string("readTexture of the display texture failed ") + when, false;
    const int colour[4] = {64, 128, 191, 255};
    for (size_t i = 0; i < pixels->size(); ++i) {
        const size_t texel = i / 4;
        const int expected[4] = {kBand[0], kBand[1], kBand[2], kBand[3]};
        const int* want = texel / w < bandRows ? expected : colour;
        if (std::abs(int((*pixels)[i]) - want[i % 4]) > 1) {
            char text[160];
            std::snprintf(text, sizeof text, "%s: texel (%zu, %zu) channel %zu is %d, expected %d", when, texel % w,
                          texel / w, i % 4, int((*pixels)[i]), want[i % 4]);
            return *error = text, false;
        }
    }
    return true;
}

bool writePpm(const char* path, const std::vector<uint8_t>& rgba, uint32_t w, uint32_t h) {
    FILE* f = std::fopen(path, "wb");
    if (!f) return false;
    std::fprintf(f, "P6\n%u %u\n255\n", w, h);
    for (size_t i = 0; i < size_t(w) * h; ++i) std::fwrite(&rgba[i * 4], 1, 3, f);
    return std::fclose(f) == 0;
}

}  // namespace

int main(int argc, char** argv) {
    std::string backendName = "vulkan";
    int frames = 60;
    const char* out = nullptr;
    bool hidden = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--backend" && i + 1 < argc) backendName = argv[++i];
        else if (a == "--frames" && i + 1 < argc) frames = std::atoi(argv[++i]);
        else if (a == "--out" && i + 1 < argc) out = argv[++i];
        else if (a == "--hidden") hidden = true;
        else return fail("usage: bricklight-viewer-backend-smoke [--backend vulkan|gl] [--frames N] [--out FILE.ppm] [--hidden]");
    }
    if (backendName != "vulkan" && backendName != "gl") return fail("--backend must be vulkan or gl");
    if (frames < 4) return fail("--frames must be at least 4 (the run resizes half-way)");

    // Every message counts as a failure: the presentation layer must be silent under validation.
    int messages = 0;
    viewer::BackendOptions options;
    options.title = "bricklight-viewer-backend-smoke";
    options.validation = true;
    options.vsync = false;
    options.hidden = hidden;
    options.errorCallback = [&messages](rhi::Severity, const std::string& m) {
        ++messages;
        std::fprintf(stderr, "message: %s\n", m.c_str());
    };

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // a test leaves no imgui.ini behind
    std::string error;
    std::unique_ptr<viewer::ViewerBackend> backend = backendName == "vulkan"
                                                         ? viewer::ViewerBackend::createVulkan(options, &error)
                                                         : viewer::ViewerBackend::createGl(options, &error);
    if (!backend) {
        ImGui::DestroyContext();
        return fail(error);
    }
    std::printf("%s: %s\n", backend->name(), backend->device().capabilities().deviceName.c_str());

    const uint32_t firstWidth = backend->displayWidth(), firstHeight = backend->displayHeight();
    std::vector<uint8_t> pixels, upload;
    const uint8_t kColour8[4] = {64, 128, 191, 255};
    int rendered = 0, attempts = 0;
    bool checkedFirst = false, resized = false;
    const auto start = std::chrono::steady_clock::now();
    const rhi::ClearValue colour{{0.25f, 0.5f, 0.75f, 1.0f}};
    while (rendered < frames && attempts++ < frames * 4) {
        glfwPollEvents();
        if (!resized && rendered == frames / 2) {
            glfwSetWindowSize(backend->window(), 640, 400);
            resized = true;
            continue;  // poll once more so the new size is seen
        }
        // Vsync on for one frame and off again: on Vulkan two new swapchains of the same size.
        if (rendered == frames * 3 / 4 || rendered == frames * 3 / 4 + 1) backend->setVsync(rendered == frames * 3 / 4);
        if (!backend->beginFrame()) continue;
        ImGui::NewFrame();
        ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_Always);
        ImGui::Begin("backend smoke", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
        ImGui::Text("%s frame %d, %ux%u", backend->name(), rendered, backend->displayWidth(), backend->displayHeight());
        ImGui::End();
        bool written = true;
        if (!resized) {
            written = backend->device().clearTexture(backend->displayTexture(), 0, 1, colour);
        } else {
            const uint32_t w = backend->displayWidth(), h = backend->displayHeight();
            upload.resize(size_t(w) * h * 4);
            for (size_t t = 0; t < size_t(w) * h; ++t)
                std::memcpy(&upload[t * 4], t / w < kBandRows ? kBand : kColour8, 4);
            written = backend->device().writeTexture(backend->displayTexture(), {}, upload.data());
        }
        ImGui::Render();
        backend->endFrame(ImGui::GetDrawData());
        if (!written) error = "clearTexture/writeTexture of the display texture failed";
        ++rendered;
        if (!checkedFirst && error.empty()) {
            checkedFirst = true;
            checkDisplay(*backend, "after the first frame", 0, &pixels, &error);
        }
        if (!error.empty()) break;
    }
    backend->waitIdle();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (error.empty() && rendered < frames) error = "only " + std::to_string(rendered) + " frames rendered";
    if (error.empty()) checkDisplay(*backend, "after the last frame", kBandRows, &pixels, &error);
    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(backend->window(), &fbWidth, &fbHeight);
    const uint32_t lastWidth = backend->displayWidth(), lastHeight = backend->displayHeight();
    if (error.empty() && (lastWidth != uint32_t(fbWidth) || lastHeight != uint32_t(fbHeight)))
        error = "the display texture is " + std::to_string(lastWidth) + "x" + std::to_string(lastHeight) +
                " but the framebuffer " + std::to_string(fbWidth) + "x" + std::to_string(fbHeight);
    if (error.empty() && lastWidth == firstWidth && lastHeight == firstHeight)
        error = "the window resize did not reach the display texture";
    if (error.empty() && out && !writePpm(out, pixels, lastWidth, lastHeight)) error = std::string("cannot write ") + out;
    backend.reset();
    ImGui::DestroyContext();
    if (error.empty() && messages) error = std::to_string(messages) + " device/validation message(s)";
    if (!error.empty()) return fail(error);
    std::printf("ok: %s, %d frames (%ux%u, then %ux%u), %.1f frames/s\n", backendName.c_str(), rendered, firstWidth,
                firstHeight, lastWidth, lastHeight, rendered / seconds);
    return 0;
}
