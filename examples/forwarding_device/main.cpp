// Runs the RHI conformance kit against a device of "your own" RHI (ForwardingDevice, which hands every call
// to one of our backends), with the kit's plain runner: what an integrator does to check an engine's RHI
// adapter before running Bricklight on it. docs/rhi.md, "Running the conformance kit on your RHI".
//
//   bricklight-forwarding-device [--backend vulkan|gl|both] [--no-barrier-hook] [case-name-part ...]
//
// Every case by default (a few seconds per backend on lavapipe/llvmpipe); name parts select cases.
// With both backends the runner also compares each case's outputs across the two. The exit code is
// nonzero when anything failed.
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "bricklight/conformance.h"
#include "bricklight/rhi_gl.h"
#include "bricklight/rhi_vulkan.h"
#include "forwarding_device.h"

using namespace bricklight;
using example::ForwardingDevice;

namespace {

struct Options {
    bool vulkan = true, gl = true;
    bool barrierHook = true;
    std::vector<std::string> filters;
};

bool parse(int argc, char** argv, Options* o) {
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--backend" && i + 1 < argc) {
            std::string b = argv[++i];
            if (b != "vulkan" && b != "gl" && b != "both") return false;
            o->vulkan = b != "gl";
            o->gl = b != "vulkan";
        } else if (a == "--no-barrier-hook") {
            o->barrierHook = false;
        } else if (a.rfind("--", 0) == 0) {
            return false;
        } else {
            o->filters.push_back(a);
        }
    }
    return true;
}

std::unique_ptr<rhi::IDevice> makeVulkanDevice() {
    vulkan::DeviceOptions options;
    // The validation layer (with synchronization validation) checks what our backend does with the records
    // the forwarding device passes on; any message fails the case.
    options.enableValidation = true;
    options.enableSyncValidation = true;
    std::unique_ptr<rhi::IDevice> inner = vulkan::createDevice(options);
    if (!inner) return nullptr;
    return std::make_unique<ForwardingDevice>(std::move(inner));
}

std::unique_ptr<rhi::IDevice> makeGlDevice() {
    std::string error;
    std::unique_ptr<rhi::IDevice> inner = gl::createHeadlessDevice(gl::HeadlessApi::Auto, nullptr, &error);
    if (!inner) {
        std::fprintf(stderr, "gl: %s\n", error.c_str());
        return nullptr;
    }
    return std::make_unique<ForwardingDevice>(std::move(inner));
}

// The barrier hook. An engine's adapter would count the barriers it places; this one asks the backend it
// forwards to. The kit calls it with the device that createDevice returned. Asked about the forwarding
// device itself, vulkan::barrierCount would be empty (not our device): the hazard cases would then skip
// their barrier checks with a note, as --no-barrier-hook shows.
std::optional<uint64_t> vulkanBarriers(rhi::IDevice& device) {
    return vulkan::barrierCount(static_cast<ForwardingDevice&>(device).inner());
}
std::optional<uint64_t> glBarriers(rhi::IDevice& device) {
    return gl::barrierCount(static_cast<ForwardingDevice&>(device).inner());
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    if (!parse(argc, argv, &o)) {
        std::fprintf(stderr, "usage: %s [--backend vulkan|gl|both] [--no-barrier-hook] [case-name-part ...]\n", argv[0]);
        return 2;
    }
    std::vector<conformance::Backend> backends;
    // One Vulkan device kept for the whole run keeps the driver loaded between the cases' devices, as an
    // application's would be (some ICDs fail to load again after many instance create/destroy cycles).
    std::unique_ptr<rhi::IDevice> keepDriverLoaded;
    if (o.vulkan) {
        keepDriverLoaded = vulkan::createDevice(vulkan::DeviceOptions{});
        backends.push_back({"forwarding-vulkan", makeVulkanDevice, o.barrierHook ? vulkanBarriers : nullptr});
    }
    if (o.gl) backends.push_back({"forwarding-gl", makeGlDevice, o.barrierHook ? glBarriers : nullptr});

    conformance::RunOptions run;
    run.filters = o.filters;
    return conformance::runAll(backends, run);
}
