// bricklight-replay: runs a recording (bricklight-render --record, rhi::createRecordingDevice) on a backend
// and reports how many calls it made and how many the device refused.
//
//   bricklight-replay FILE [--backend vulkan|gl|null] [--validate] [--quiet] [--max-invocations N]
//                          [--max-vertices N] [--max-bytes N] [--max-marker-depth N]
//
// Exit codes: 0 every line was understood and every call accepted with no error reported; 1 a call failed
// or the device reported an error; 2 usage, or the file cannot be read; 3 the recording is malformed (a
// line that cannot be understood: the lines before it have run); 4 the backend could not be created; 5 a
// line asks for more work or memory than the budget (rhi::ReplayOptions; the lines before it have run).
// See docs/rhi.md §7.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "bricklight/rhi_validation.h"
#include "bricklight/version.h"
#ifdef BRICKLIGHT_REPLAY_VULKAN
#include "bricklight/rhi_vulkan.h"
#endif
#ifdef BRICKLIGHT_REPLAY_GL
#include "bricklight/rhi_gl.h"
#endif

// Every shader a recording of ours may name, registered by the anchors of the libraries that embed them
// (linking the object libraries of the example and test shaders registers those by themselves).
namespace bricklight::shaders {
void link_bricklight_sdf();
void link_bricklight_gi();
void link_bricklight_vct();
void link_bricklight_shadows();
void link_bricklight_reflections();
void link_bricklight_gbuffer();
void link_bricklight_rhi_test_shaders();
}  // namespace bricklight::shaders

using namespace bricklight;

namespace {

enum Exit { Ok = 0, CallFailed = 1, Usage = 2, Malformed = 3, NoBackend = 4, OverBudget = 5 };

const char kUsage[] =
    "usage: bricklight-replay FILE [--backend vulkan|gl|null] [--validate] [--quiet] [budgets]\n"
    "  Replays a recording (one JSON call per line, as bricklight-render --record writes it) on a backend.\n"
    "  --backend   vulkan (default), gl (headless) or null (executes nothing, checks nothing)\n"
    "  --validate  every call through the validation wrapper (rhi::createValidationDevice)\n"
    "  --quiet     no per-message output, only the summary\n"
    "  --help, --version\n"
    "budgets (a line past one stops the replay, exit 5):\n"
    "  --max-invocations N   invocations of one dispatch, groups x local size (default 268435456)\n"
    "  --max-vertices N      vertices (indices) x instances of one draw (default 268435456)\n"
    "  --max-bytes N         bytes of the textures and buffers alive at once (default 1073741824)\n"
    "  --max-marker-depth N  markers open at once (default 32, also the most the devices take)\n"
    "exit codes: 0 ok; 1 a call failed or an error was reported; 2 usage or unreadable file;\n"
    "            3 malformed recording; 4 the backend could not be created; 5 over a budget\n";

struct Options {
    std::string file, backend = "vulkan";
    bool validate = false, quiet = false;
    rhi::ReplayOptions replay;
};

[[noreturn]] void usage(const std::string& problem) {
    std::fprintf(stderr, "bricklight-replay: %s\n%s", problem.c_str(), kUsage);
    std::exit(Usage);
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            std::exit(Ok);
        } else if (a == "--version") {
            std::printf("bricklight-replay %s\n", BRICKLIGHT_VERSION_STRING);
            std::exit(Ok);
        } else if (a == "--backend") {
            if (++i >= argc) usage("--backend needs a value");
            o.backend = argv[i];
            if (o.backend != "vulkan" && o.backend != "gl" && o.backend != "null") usage("unknown backend '" + o.backend + "'");
        } else if (a == "--validate") {
            o.validate = true;
        } else if (a == "--quiet") {
            o.quiet = true;
        } else if (a == "--max-invocations" || a == "--max-vertices" || a == "--max-bytes" || a == "--max-marker-depth") {
            if (++i >= argc) usage(a + " needs a value");
            const std::string v = argv[i];
            char* end = nullptr;
            errno = 0;
            const unsigned long long n = v.empty() || v[0] == '-' ? 0 : std::strtoull(v.c_str(), &end, 10);
            if (!end || *end || errno || n == 0) usage(a + ": '" + v + "' is not a positive whole number");
            if (a == "--max-invocations") o.replay.maxDispatchInvocations = n;
            else if (a == "--max-vertices") o.replay.maxDrawVertices = n;
            else if (a == "--max-bytes") o.replay.maxLiveBytes = n;
            else if (n > rhi::kMaxMarkerDepth) usage(a + ": at most " + std::to_string(rhi::kMaxMarkerDepth) + " (rhi::kMaxMarkerDepth)");
            else o.replay.maxMarkerDepth = uint32_t(n);
        } else if (a.rfind("--", 0) == 0) {
            usage("unknown option '" + a + "'");
        } else if (o.file.empty()) {
            o.file = a;
        } else {
            usage("more than one recording given ('" + o.file + "', '" + a + "')");
        }
    }
    if (o.file.empty()) usage("no recording given");
    return o;
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parse(argc, argv);
    shaders::link_bricklight_sdf();
    shaders::link_bricklight_gi();
    shaders::link_bricklight_vct();
    shaders::link_bricklight_shadows();
    shaders::link_bricklight_reflections();
    shaders::link_bricklight_gbuffer();
    shaders::link_bricklight_rhi_test_shaders();

    // A regular file only: a device or a pipe (/dev/zero) would be read without end.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(o.file, ec)) {
        std::fprintf(stderr, "bricklight-replay: '%s' is not a readable regular file\n", o.file.c_str());
        return Usage;
    }
    std::ifstream in(o.file, std::ios::binary);
    if (!in) {
        std::fprintf(stderr, "bricklight-replay: cannot open '%s': %s\n", o.file.c_str(), std::strerror(errno));
        return Usage;
    }

    uint64_t errors = 0;
    const rhi::ErrorCallback report = [&](rhi::Severity s, const std::string& m) {
        if (s == rhi::Severity::Info) return;
        if (s == rhi::Severity::Error) ++errors;
        if (!o.quiet) std::fprintf(stderr, "bricklight-replay: %s: %s\n", s == rhi::Severity::Error ? "error" : "warning", m.c_str());
    };
    std::unique_ptr<rhi::IDevice> backend, wrapper;
    std::string error;
    if (o.backend == "vulkan") {
#ifdef BRICKLIGHT_REPLAY_VULKAN
        vulkan::DeviceOptions options;
        options.errorCallback = report;
        backend = vulkan::createDevice(options);
#else
        error = "this build has no Vulkan backend (BRICKLIGHT_VULKAN=OFF)";
#endif
    } else if (o.backend == "gl") {
#ifdef BRICKLIGHT_REPLAY_GL
        backend = gl::createHeadlessDevice(gl::HeadlessApi::Auto, report, &error);
#else
        error = "this build has no GL backend (BRICKLIGHT_GL=OFF)";
#endif
    } else {
        backend = rhi::createNullDevice();
        backend->setErrorCallback(report);
    }
    if (!backend) {
        std::fprintf(stderr, "bricklight-replay: no %s device%s%s\n", o.backend.c_str(), error.empty() ? "" : ": ", error.c_str());
        return NoBackend;
    }
    rhi::IDevice* device = backend.get();
    if (o.validate) {
        wrapper = rhi::createValidationDevice(*backend);
        wrapper->setErrorCallback(report);
        device = wrapper.get();
    }

    rhi::ReplayOptions options = o.replay;
    options.onFailedCall = [&](uint64_t line, const std::string& call) {
        if (!o.quiet) std::fprintf(stderr, "bricklight-replay: line %llu: %s failed\n", (unsigned long long)line, call.c_str());
    };
    rhi::ReplayStats stats;
    const bool understood = rhi::replayRecording(in, *device, options, &stats, &error);
    device->waitIdle();  // work still in flight may report errors too
    std::printf("bricklight-replay: %s on %s%s: %llu calls, %llu failed", o.file.c_str(), device->capabilities().deviceName.c_str(),
                o.validate ? " (validated)" : "", (unsigned long long)stats.calls, (unsigned long long)stats.failedCalls);
    if (stats.failedCalls) std::printf(" (first at line %llu)", (unsigned long long)stats.firstFailedLine);
    std::printf(", %llu error(s) reported\n", (unsigned long long)errors);
    if (!understood) {
        std::fprintf(stderr, "bricklight-replay: %s: %s\n", o.file.c_str(), error.c_str());
        return stats.overBudget ? OverBudget : Malformed;
    }
    return stats.failedCalls || errors ? CallFailed : Ok;
}
