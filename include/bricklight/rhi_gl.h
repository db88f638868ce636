// Bricklight OpenGL 4.5 reference backend (bricklight::gl). It runs on the GL context that is current on
// the calling thread (the app's, through createDevice) or on a headless one it creates itself (OSMesa,
// EGL or WGL, through createHeadlessDevice). No GL library is linked: everything is loaded at run time, so a
// program that links bricklight_gl runs where only libEGL (or only libOSMesa) exists.
// docs/backend_gl.md says how the records map to GL and which GL state a call leaves changed.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "bricklight/rhi.h"

namespace bricklight::gl {

using GetProcAddress = void* (*)(const char* name);

struct DeviceOptions {
    GetProcAddress getProcAddress = nullptr;  // required: from the app's context (glfwGetProcAddress, ...)
    bool debugOutput = true;                  // KHR_debug: GL errors -> errorCallback (Severity::Error)
    rhi::ErrorCallback errorCallback;         // if empty -> stderr
};

// Uses the context current on this thread (it must stay current whenever the device is called);
// returns nullptr, with the reason through the callback, if it is not GL 4.5 core or lacks a function.
std::unique_ptr<rhi::IDevice> createDevice(const DeviceOptions& options);

// Auto: env BRICKLIGHT_GL_CONTEXT=osmesa|egl|wgl, else on Windows WGL, elsewhere OSMesa, then EGL.
enum class HeadlessApi { Auto, OSMesa, EGL, WGL };

// A GL 4.5 core context with no window. OSMesa renders into a tiny client buffer that nothing uses (all
// rendering goes to framebuffer objects); EGL uses EGL_EXT_platform_device when present (a GPU machine
// with no display), else Mesa's surfaceless platform or the default display, with no surface at all; WGL
// (Windows) makes its context on a hidden 1x1 window of its own, which only the creating thread can destroy:
// destroy a WGL context (or the device that owns it) on the thread that created it.
class HeadlessContext {
public:
    static std::unique_ptr<HeadlessContext> create(HeadlessApi api, std::string* error);
    virtual ~HeadlessContext() = default;
    virtual void makeCurrent() = 0;
    virtual bool isCurrent() const = 0;
    virtual GetProcAddress getProcAddress() const = 0;
    virtual const char* apiName() const = 0;  // "osmesa", "egl" or "wgl"

protected:
    HeadlessContext() = default;
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;
};

// Convenience for tests and tools: a headless context plus a device that owns it (the context is
// destroyed after the device, and made current again by every call if another context took over).
std::unique_ptr<rhi::IDevice> createHeadlessDevice(HeadlessApi api, rhi::ErrorCallback callback,
                                                   std::string* error);

// Number of glMemoryBarrier calls the device has issued, so that tests can check that read-after-read and
// order-independent writers emit none. Empty for a device that is not this backend's own (e.g. one under
// the validation wrapper, or an application's device that forwards to ours): that device cannot tell.
std::optional<uint64_t> barrierCount(rhi::IDevice& device);

}  // namespace bricklight::gl
