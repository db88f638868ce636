// bricklight-conformance-run: the conformance kit's plain runner (conformance::runAll) on our own backends,
// with no test framework: the program a platform without Catch2 runs (the Windows build, under Wine; ctest
// label "windows"). Each case gets a new device under the kit's validation wrapper; with both backends the
// runner also compares every case's outputs across the two.
//
//   bricklight-conformance-run [--backend vulkan|gl|both] [--vulkan-validation auto|on|off] [case-name-part ...]
//
// auto (the default) enables VK_LAYER_KHRONOS_validation (with synchronization validation) where it is
// installed and says so where it is not (Wine's vulkan-1.dll has no Windows layers): "on" makes its absence
// an error. The exit code is nonzero when anything failed.
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "bricklight/conformance.h"
#include "bricklight/rhi_gl.h"
#include "bricklight/rhi_vulkan.h"

using namespace bricklight;

namespace {

struct Options {
    bool vulkan = true, gl = true;
    std::string validation = "auto";
    std::vector<std::string> filters;
};

bool parse(int argc, char** argv, Options* o) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--backend" && i + 1 < argc) {
            const std::string b = argv[++i];
            if (b != "vulkan" && b != "gl" && b != "both") return false;
            o->vulkan = b != "gl";
            o->gl = b != "vulkan";
        } else if (a == "--vulkan-validation" && i + 1 < argc) {
            o->validation = argv[++i];
            if (o->validation != "auto" && o->validation != "on" && o->validation != "off") return false;
        } else if (a.rfind("--", 0) == 0) {
            return false;
        } else {
            o->filters.push_back(a);
        }
    }
    return true;
}

bool validationLayerInstalled() {
    uint32_t count = 0;
    if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
    std::vector<VkLayerProperties> layers(count);
    if (vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
    for (const VkLayerProperties& l : layers)
        if (!std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation")) return true;
    return false;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    if (!parse(argc, argv, &o)) {
        std::fprintf(stderr,
                     "usage: %s [--backend vulkan|gl|both] [--vulkan-validation auto|on|off] [case-name-part ...]\n", argv[0]);
        return 2;
    }
    std::vector<conformance::Backend> backends;
    // One Vulkan device kept for the whole run keeps the driver loaded between the cases' devices, as an
    // application's would be.
    std::unique_ptr<rhi::IDevice> keepDriverLoaded;
    if (o.vulkan) {
        const bool layer = o.validation != "off" && validationLayerInstalled();
        if (o.validation == "on" && !layer) {
            std::fprintf(stderr, "bricklight-conformance-run: --vulkan-validation on, but VK_LAYER_KHRONOS_validation is not installed\n");
            return 1;
        }
        if (o.validation == "auto" && !layer)
            std::printf("note: VK_LAYER_KHRONOS_validation is not installed: Vulkan runs under the kit's validation wrapper only\n");
        vulkan::DeviceOptions options;
        options.enableValidation = layer;
        options.enableSyncValidation = layer;
        keepDriverLoaded = vulkan::createDevice(vulkan::DeviceOptions{});
        backends.push_back({"vulkan", [options] { return vulkan::createDevice(options); },
                            [](rhi::IDevice& d) { return vulkan::barrierCount(d); }});
    }
    if (o.gl)
        backends.push_back({"gl",
                            [] {
                                std::string error;
                                auto device = gl::createHeadlessDevice(gl::HeadlessApi::Auto, nullptr, &error);
                                if (!device) std::fprintf(stderr, "gl: %s\n", error.c_str());
                                return device;
                            },
                            [](rhi::IDevice& d) { return gl::barrierCount(d); }});
    conformance::RunOptions run;
    run.filters = o.filters;
    return conformance::runAll(backends, run);
}
