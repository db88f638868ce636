// The conformance suite on our reference backends: every case on Vulkan (validation layer on, any
// message fails the case), on OpenGL 4.5, and compared across the two.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <string>

#include "bricklight/conformance_catch2.h"
#ifdef BRICKLIGHT_HAS_VULKAN
#include "bricklight/rhi_vulkan.h"
#endif
#ifdef BRICKLIGHT_HAS_GL
#include "bricklight/rhi_gl.h"
#endif

using namespace bricklight;

int main(int argc, char** argv) {
    std::vector<conformance::Backend> backends;
#ifdef BRICKLIGHT_HAS_VULKAN
    // Each case creates and destroys its own instance. The loader unloads the ICD with the last instance,
    // and NVIDIA's ICD stops loading after ~30 such cycles in one process (seen on an H200: "Could not get
    // 'vkCreateInstance' ... for ICD libGLX_nvidia.so.0"). One instance kept for the whole run keeps the
    // ICD loaded, as an application's would be.
    std::unique_ptr<rhi::IDevice> keepDriverLoaded;
    bool listing = false;
    for (int i = 1; i < argc; ++i) listing |= std::string(argv[i]).rfind("--list", 0) == 0;
    if (!listing) keepDriverLoaded = vulkan::createDevice(vulkan::DeviceOptions{});
    backends.push_back({"vulkan",
                        [] {
                            vulkan::DeviceOptions options;
                            options.enableValidation = true;
                            // Synchronization validation turns a missed barrier into a failing message even on
                            // drivers that run every dispatch in order (lavapipe).
                            options.enableSyncValidation = true;
                            return vulkan::createDevice(options);
                        },
                        [](rhi::IDevice& d) { return vulkan::barrierCount(d); }});
#endif
#ifdef BRICKLIGHT_HAS_GL
    backends.push_back({"gl",
                        []() -> std::unique_ptr<rhi::IDevice> {
                            std::string error;
                            auto device = gl::createHeadlessDevice(gl::HeadlessApi::Auto, nullptr, &error);
                            if (!device) fprintf(stderr, "gl: %s\n", error.c_str());
                            return device;
                        },
                        [](rhi::IDevice& d) { return gl::barrierCount(d); }});
#endif
    conformance::registerCatchTests(backends);
    return Catch::Session().run(argc, argv);
}
