#include "test_device.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "bricklight/rhi_validation.h"
#ifdef BRICKLIGHT_HAS_VULKAN
#include "bricklight/rhi_vulkan.h"
#endif
#ifdef BRICKLIGHT_HAS_GL
#include "bricklight/rhi_gl.h"
#endif

namespace bricklight::testing {

namespace {
bool validationWrapperWanted() {
    const char* v = std::getenv("BRICKLIGHT_TEST_VALIDATION_WRAPPER");
    return !v || std::strcmp(v, "0") != 0;
}
}  // namespace

TestDevice makeDevice(const std::string& backend) {
    TestDevice t;
    t.backend = backend;
    auto messages = t.messages;
    // Info lines are the backend's driver statistics (on request), not faults; the wrapper's own messages
    // are all warnings or errors, so every one of them counts.
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
        t.backendDevice = vulkan::createDevice(options);
    }
#endif
#ifdef BRICKLIGHT_HAS_GL
    if (backend == "gl") {
        std::string error;
        t.backendDevice = gl::createHeadlessDevice(gl::HeadlessApi::Auto, callback, &error);
        if (!t.backendDevice) std::fprintf(stderr, "gl: %s\n", error.c_str());
    }
#endif
    if (!t.backendDevice) return t;
    if (validationWrapperWanted()) {
        t.wrapper = rhi::createValidationDevice(*t.backendDevice);
        t.wrapper->setErrorCallback(callback);  // the wrapper's messages and the backend's, forwarded
        t.device = t.wrapper.get();
    } else {
        t.device = t.backendDevice.get();
    }
    return t;
}

}  // namespace bricklight::testing
