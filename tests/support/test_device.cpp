#include "test_device.h"

#include <cstdio>

#ifdef BRICKLIGHT_HAS_VULKAN
#include "bricklight/rhi_vulkan.h"
#endif
#ifdef BRICKLIGHT_HAS_GL
#include "bricklight/rhi_gl.h"
#endif

namespace bricklight::testing {

TestDevice makeDevice(const std::string& backend) {
    TestDevice t;
    t.backend = backend;
    auto messages = t.messages;
    rhi::ErrorCallback callback = [messages](rhi::Severity s, const std::string& m) {
        if (s != rhi::Severity::Info) messages->push_back(m);
    };
#ifdef BRICKLIGHT_HAS_VULKAN
    if (backend == "vulkan") {
        vulkan::DeviceOptions options;
        options.enableValidation = true;
        // Synchronization validation turns a barrier the builder's records should have caused into a
        // failing message even on lavapipe, which runs dispatches in order.
        options.enableSyncValidation = true;
        options.errorCallback = callback;
        t.device = vulkan::createDevice(options);
    }
#endif
#ifdef BRICKLIGHT_HAS_GL
    if (backend == "gl") {
        std::string error;
        t.device = gl::createHeadlessDevice(gl::HeadlessApi::Auto, callback, &error);
        if (!t.device) std::fprintf(stderr, "gl: %s\n", error.c_str());
    }
#endif
    return t;
}

}  // namespace bricklight::testing
