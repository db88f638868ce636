// bricklight-viewer's window, device and presentation layer: a GLFW window, a Bricklight device on that
// window's API (Vulkan embedded on the viewer's own VkDevice, or GL on the window's context), a display
// texture that the app's passes write and that is copied to the window each frame, and Dear ImGui on top.
// The app owns the ImGui context (ImGui::CreateContext before create*, DestroyContext after the backend).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "bricklight/rhi.h"

struct GLFWwindow;
struct ImDrawData;

namespace bricklight::viewer {

struct BackendOptions {
    uint32_t width = 1280, height = 720;  // window size in screen coordinates
    std::string title = "bricklight-viewer";
    bool vsync = true;
    // Vulkan: VK_LAYER_KHRONOS_validation + a debug messenger; messages go to errorCallback as
    // Severity::Error "vulkan validation: ..." (also on with env BRICKLIGHT_VK_VALIDATION=1).
    // GL: KHR_debug (the GL device's debugOutput). Both: device() is our validation wrapper
    // (rhi::createValidationDevice) over the backend, so every record is checked against its shaders.
    bool validation = false;
    bool hidden = false;               // create the window invisible (tests)
    rhi::ErrorCallback errorCallback;  // every device/validation message; empty: stderr
};

class ViewerBackend {
public:
    // The options' callback, or one that prints to stderr: backends store the result (its address goes to
    // the Vulkan messenger and ImGui), so it is never empty.
    static rhi::ErrorCallback callbackOrStderr(const rhi::ErrorCallback& callback);
    // nullptr + *error (one clear line) when there is no display, no Vulkan 1.3 device with a
    // present-capable graphics+compute queue, no GL 4.5 core context, ... Never crashes.
    static std::unique_ptr<ViewerBackend> createVulkan(const BackendOptions& options, std::string* error);
    static std::unique_ptr<ViewerBackend> createGl(const BackendOptions& options, std::string* error);

    virtual ~ViewerBackend() = default;
    virtual const char* name() const = 0;  // "vulkan" / "gl"
    virtual GLFWwindow* window() = 0;
    // Vulkan: our backend in embedded mode on the viewer's VkDevice/queue; GL: on the window's context.
    virtual rhi::IDevice& device() = 0;

    // Polls nothing. Acquires the swapchain image (Vulkan), begins this frame's command buffer and hands it
    // to the device, starts the ImGui platform/renderer frame (the caller then calls ImGui::NewFrame()).
    // Recreates the swapchain / display texture when the framebuffer size changed. Returns false (and
    // records nothing; do not call endFrame) while the framebuffer is 0x0 (minimized).
    virtual bool beginFrame() = 0;

    // The picture of this frame: RGBA8_UNORM, framebuffer-sized, Storage | Sampled | RenderTarget, holding
    // display-ready (sRGB-encoded) bytes; row 0 is the top of the window. A native object of the backend
    // wrapped with wrapNativeTexture. Valid from beginFrame until the next size change.
    virtual rhi::TextureHandle displayTexture() = 0;
    virtual uint32_t displayWidth() const = 0;
    virtual uint32_t displayHeight() const = 0;

    // Copies the display texture to the window, draws `ui` (may be null) on top, submits, presents, then
    // calls device().endFrame(). Until the next beginFrame the device records into its own command
    // buffers, so blocking read-backs work between frames.
    virtual void endFrame(ImDrawData* ui) = 0;

    // True once the window or device failed for good (a lost surface or device, a swapchain or display
    // texture that cannot be created, a failed submit): beginFrame then keeps returning false, and the app
    // must end instead of waiting as for a minimized window.
    virtual bool failed() const = 0;
    virtual void setVsync(bool on) = 0;  // Vulkan: FIFO vs MAILBOX/IMMEDIATE; GL: glfwSwapInterval
    virtual void waitIdle() = 0;         // vkDeviceWaitIdle / glFinish
};

}  // namespace bricklight::viewer
