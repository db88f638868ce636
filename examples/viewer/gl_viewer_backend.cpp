// OpenGL 4.5 core presentation for bricklight-viewer: the GL device runs on the window's own context
// (gl::createDevice with glfwGetProcAddress); the display texture is a GL texture of ours that the device
// only wraps (wrapNativeTexture), and each frame is blitted from an FBO on it to the default framebuffer.
#define GLFW_INCLUDE_NONE
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cstdio>

#include "bricklight/rhi_gl.h"
#include "bricklight/rhi_validation.h"
#include "glfw_errors.h"
#include "viewer_backend.h"

namespace bricklight::viewer {

namespace {

using rhi::Severity;

void* loadGl(const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); }

// The few GL entry points we call ourselves; no loader library (the device and ImGui load their own).
#define BL_VIEWER_GL_FUNCTIONS(X)                                       \
    X(PFNGLCREATETEXTURESPROC, glCreateTextures)                        \
    X(PFNGLTEXTURESTORAGE2DPROC, glTextureStorage2D)                    \
    X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                        \
    X(PFNGLCREATEFRAMEBUFFERSPROC, glCreateFramebuffers)                \
    X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)                \
    X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, glNamedFramebufferTexture)      \
    X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, glNamedFramebufferReadBuffer) \
    X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, glCheckNamedFramebufferStatus) \
    X(PFNGLBLITNAMEDFRAMEBUFFERPROC, glBlitNamedFramebuffer)            \
    X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                      \
    X(PFNGLMEMORYBARRIERPROC, glMemoryBarrier)                          \
    X(PFNGLDISABLEPROC, glDisable)                                      \
    X(PFNGLVIEWPORTPROC, glViewport)                                    \
    X(PFNGLFINISHPROC, glFinish)

struct GlFunctions {
#define BL_DECLARE(type, name) type name = nullptr;
    BL_VIEWER_GL_FUNCTIONS(BL_DECLARE)
#undef BL_DECLARE
    // Returns the first missing function's name, or null.
    const char* load() {
#define BL_LOAD(type, name)                                          \
    name = reinterpret_cast<type>(glfwGetProcAddress(#name));        \
    if (!name) return #name;
        BL_VIEWER_GL_FUNCTIONS(BL_LOAD)
#undef BL_LOAD
        return nullptr;
    }
};

class GlViewerBackend final : public ViewerBackend {
public:
    explicit GlViewerBackend(const BackendOptions& options) : options_(options) {
        errorCallback_ = callbackOrStderr(options.errorCallback);
    }
    ~GlViewerBackend() override;

    bool create(std::string* error);

    const char* name() const override { return "gl"; }
    GLFWwindow* window() override { return window_; }
    rhi::IDevice& device() override { return api(); }
    bool failed() const override { return failed_; }
    bool beginFrame() override;
    rhi::TextureHandle displayTexture() override { return displayHandle_; }
    uint32_t displayWidth() const override { return width_; }
    uint32_t displayHeight() const override { return height_; }
    void endFrame(ImDrawData* ui) override;
    void setVsync(bool on) override {
        glfwMakeContextCurrent(window_);
        glfwSwapInterval(on ? 1 : 0);
    }
    void waitIdle() override {
        if (gl_.glFinish) gl_.glFinish();
    }

private:
    bool createDisplay(uint32_t width, uint32_t height, std::string* error);
    void destroyDisplay();

    BackendOptions options_;
    rhi::ErrorCallback errorCallback_;
    bool glfwReady_ = false;
    GLFWwindow* window_ = nullptr;
    bool imguiGlfw_ = false, imguiGl_ = false;
    GlFunctions gl_;
    std::unique_ptr<rhi::IDevice> device_;
    bool failed_ = false;
    std::unique_ptr<rhi::IDevice> validation_;  // rhi::createValidationDevice over device_ with options.validation
    // What the app and our own calls use: the validation wrapper when there is one (it must see every
    // resource the app's records name, the wrapped display texture too).
    rhi::IDevice& api() { return validation_ ? *validation_ : *device_; }
    GLuint texture_ = 0, framebuffer_ = 0;
    rhi::TextureHandle displayHandle_;
    uint32_t width_ = 0, height_ = 0;
    bool inFrame_ = false;
};

bool GlViewerBackend::createDisplay(uint32_t width, uint32_t height, std::string* error) {
    // Immutable storage: the device makes views of wrapped textures only when their storage is immutable.
    gl_.glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    gl_.glTextureStorage2D(texture_, 1, GL_RGBA8, GLsizei(width), GLsizei(height));
    gl_.glCreateFramebuffers(1, &framebuffer_);
    gl_.glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, texture_, 0);
    gl_.glNamedFramebufferReadBuffer(framebuffer_, GL_COLOR_ATTACHMENT0);
    if (gl_.glCheckNamedFramebufferStatus(framebuffer_, GL_READ_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return *error = "gl: the display texture's framebuffer is incomplete", false;
    rhi::TextureDesc desc;
    desc.format = rhi::Format::RGBA8_UNORM;
    desc.width = width;
    desc.height = height;
    desc.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled | rhi::TextureUsage::RenderTarget;
    desc.debugName = "viewer display";
    displayHandle_ = api().wrapNativeTexture(desc, {texture_, 0});
    if (!displayHandle_) return *error = "gl: wrapNativeTexture refused the display texture", false;
    width_ = width;
    height_ = height;
    return true;
}

void GlViewerBackend::destroyDisplay() {
    if (displayHandle_) api().destroy(displayHandle_);  // drops the device's views/FBOs of it first
    if (framebuffer_) gl_.glDeleteFramebuffers(1, &framebuffer_);
    if (texture_) gl_.glDeleteTextures(1, &texture_);
    displayHandle_ = {};
    framebuffer_ = texture_ = 0;
    width_ = height_ = 0;
}

bool GlViewerBackend::create(std::string* error) {
    captureGlfwErrors();
    if (!glfwInit())
        return *error = "no display: set DISPLAY or run under Xvfb (docs/viewer.md) [GLFW: " + lastGlfwError() + "]", false;
    glfwReady_ = true;
    if (!ImGui::GetCurrentContext()) return *error = "gl: no ImGui context (call ImGui::CreateContext first)", false;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options_.validation ? GLFW_TRUE : GLFW_FALSE);
    // The display texture holds sRGB-encoded bytes already; the blit must copy them unchanged.
    glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_FALSE);
    glfwWindowHint(GLFW_DEPTH_BITS, 0);
    glfwWindowHint(GLFW_STENCIL_BITS, 0);
    glfwWindowHint(GLFW_VISIBLE, options_.hidden ? GLFW_FALSE : GLFW_TRUE);
    window_ = glfwCreateWindow(int(options_.width), int(options_.height), options_.title.c_str(), nullptr, nullptr);
    if (!window_) return *error = "gl: no OpenGL 4.5 core context for a window: " + lastGlfwError(), false;
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(options_.vsync ? 1 : 0);
    if (const char* missing = gl_.load()) return *error = std::string("gl: the context lacks ") + missing, false;

    std::string deviceError;
    gl::DeviceOptions o;
    o.getProcAddress = loadGl;
    o.debugOutput = options_.validation;
    o.errorCallback = [this, &deviceError](Severity s, const std::string& m) {
        if (s == Severity::Error && deviceError.empty()) deviceError = m;
        errorCallback_(s, m);
    };
    device_ = gl::createDevice(o);
    if (!device_) return *error = "gl: createDevice failed: " + deviceError, false;
    device_->setErrorCallback(errorCallback_);
    if (options_.validation) {  // and our own wrapper: every record checked against its shader's reflection
        validation_ = rhi::createValidationDevice(*device_);
        validation_->setErrorCallback(errorCallback_);
    }

    imguiGlfw_ = ImGui_ImplGlfw_InitForOpenGL(window_, true);
    if (!imguiGlfw_) return *error = "gl: ImGui_ImplGlfw_InitForOpenGL failed", false;
    imguiGl_ = ImGui_ImplOpenGL3_Init("#version 450");
    if (!imguiGl_) return *error = "gl: ImGui_ImplOpenGL3_Init failed", false;

    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
    return createDisplay(uint32_t(std::max(fbWidth, 1)), uint32_t(std::max(fbHeight, 1)), error);
}

GlViewerBackend::~GlViewerBackend() {
    if (window_) glfwMakeContextCurrent(window_);
    if (imguiGl_) ImGui_ImplOpenGL3_Shutdown();
    if (imguiGlfw_) ImGui_ImplGlfw_Shutdown();
    if (device_) destroyDisplay();
    validation_.reset();
    device_.reset();  // needs the context current: it deletes its GL objects
    if (window_) glfwDestroyWindow(window_);
    if (glfwReady_) glfwTerminate();
}

bool GlViewerBackend::beginFrame() {
    if (inFrame_) return errorCallback_(Severity::Error, "gl viewer: beginFrame called twice without endFrame"), false;
    glfwMakeContextCurrent(window_);
    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
    if (failed_ || fbWidth <= 0 || fbHeight <= 0) return false;  // failed, or minimized
    if (uint32_t(fbWidth) != width_ || uint32_t(fbHeight) != height_) {
        destroyDisplay();
        std::string error;
        if (!createDisplay(uint32_t(fbWidth), uint32_t(fbHeight), &error)) {
            failed_ = true;  // no display texture: no frame can be shown
            return errorCallback_(Severity::Error, error), false;
        }
    }
    inFrame_ = true;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    return true;
}

void GlViewerBackend::endFrame(ImDrawData* ui) {
    if (!inFrame_) return errorCallback_(Severity::Error, "gl viewer: endFrame without a successful beginFrame");
    inFrame_ = false;
    // The app's image stores are incoherent with the blit's framebuffer reads, and the device orders only
    // its own calls.
    gl_.glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    // State the device may leave behind (docs/backend_gl.md) that would clip or re-encode the blit.
    gl_.glDisable(GL_SCISSOR_TEST);
    gl_.glDisable(GL_FRAMEBUFFER_SRGB);
    gl_.glDisable(GL_RASTERIZER_DISCARD);
    // Row 0 of the texture is the top of the window; GL's window origin is the bottom, so flip.
    gl_.glBlitNamedFramebuffer(framebuffer_, 0, 0, 0, GLint(width_), GLint(height_), 0, GLint(height_),
                               GLint(width_), 0, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    gl_.glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl_.glViewport(0, 0, GLsizei(width_), GLsizei(height_));
    if (ui) ImGui_ImplOpenGL3_RenderDrawData(ui);
    glfwSwapBuffers(window_);
    api().endFrame();
}

}  // namespace

std::unique_ptr<ViewerBackend> ViewerBackend::createGl(const BackendOptions& options, std::string* error) {
    std::string ignored;
    if (!error) error = &ignored;
    auto backend = std::make_unique<GlViewerBackend>(options);
    if (!backend->create(error)) return nullptr;
    return backend;
}

}  // namespace bricklight::viewer
