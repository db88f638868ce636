// bricklight-render: scene in, image out.
//
//   bricklight-render [--scene NAME|FILE] [--backend vulkan|gl] [--width W] [--height H] [--frames N]
//                     [--camera EX,EY,EZ,AX,AY,AZ] [--out FILE.png|.exr] [--aov NAME ...] [--reference --spp N]
//                     [--exposure E] [--gi sdf|none] [--gi-scale 100|75|50|25] [--gi-debug VIEW ...]
//                     [--single-bounce] [--validate] [--record FILE.jsonl] [--help] [--version]
//
// Exit status: 0 the image(s) were written; 1 the render failed (the scene, the device, an error any layer
// reported during the render, or a write; nothing half-written is left); 2 a usage error (nothing done).
//
// Without --reference: a rasterized G-buffer, direct lighting and GI from the sparse brick distance field
// (--gi sdf, the default; over --frames frames the bounces accumulate); with it, the path tracer (the
// ground truth). AOVs go next to --out as <stem>.<aov>.exr (linear float). --single-bounce keeps indirect
// light to one bounce on both paths (the path tracer stops after one; GI is fed direct light only), to
// measure GI's gather apart from its multi-bounce feedback. See docs/render.md.
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "bricklight/rhi_gl.h"
#include "bricklight/rhi_validation.h"
#include "bricklight/rhi_vulkan.h"
#include "bricklight/version.h"
#include "image_io.h"
#include "output_file.h"
#include "path_tracer.h"
#include "raster_renderer.h"
#include "scene_geometry.h"

using namespace bricklight;

namespace {

struct Options {
    std::string scene = "cornell";
    std::string backend = "vulkan";
    uint32_t width = 256, height = 256, frames = 1, spp = 64;
    bool reference = false;
    bool haveCamera = false;
    float camera[6] = {};
    std::string out = "out/render.png";
    std::vector<render::Aov> aovs;
    float exposure = 1.0f;
    bool gi = true;
    bricklight::gi::InternalResolution giScale = bricklight::gi::InternalResolution::Native;
    bool framesGiven = false;
    std::vector<std::string> giDebug;
    bool singleBounce = false;
    bool validate = false;  // every call through rhi::createValidationDevice
    std::string record;     // --record: every device call of the render as JSON lines
    scenes::LoadLimits limits;  // what a model file may cost (docs/render.md, "Untrusted files")
};

const char* const kGiDebugNames[] = {"radiance-cache", "irradiance-cache", "probes", "probe-sh", "disocclusion", "samples"};

void printUsage(FILE* to) {
    std::fprintf(to,
                 "usage: bricklight-render [--scene NAME|FILE] [--backend vulkan|gl] [--width W] [--height H]\n"
                 "                         [--frames N] [--camera EX,EY,EZ,AX,AY,AZ] [--out FILE.png|.exr]\n"
                 "                         [--aov combined|direct|indirect-diffuse|albedo|normal|depth ...]\n"
                 "                         [--reference --spp N] [--exposure E] [--gi sdf|none]\n"
                 "                         [--gi-scale 100|75|50|25] [--gi-debug VIEW ...] [--single-bounce]\n"
                 "                         [--validate] [--record FILE.jsonl] [--help] [--version]\n"
                 "                         [--max-file-bytes N] [--max-json-bytes N] [--max-json-depth N]\n"
                 "                         [--max-vertices N] [--max-indices N] [--max-face-indices N] [--max-nodes N]\n"
                 "                         [--max-node-depth N] [--max-texture-pixels N] [--allow-outside-paths]\n"
                 "                         [--import-timeout SECONDS] [--import-memory BYTES]\n"
                 "scenes: %s\n"
                 "exit status: 0 written; 1 the render failed; 2 usage error (docs/render.md)\n",
                 scenes::builtinSceneNames());
}

[[noreturn]] void usage(const std::string& problem) {
    std::fprintf(stderr, "bricklight-render: %s\n", problem.c_str());
    printUsage(stderr);
    std::exit(2);
}

// A whole number in lo..hi, read as a number: digits only (no sign, so "-18446744073709551615" cannot wrap
// around), no overflow.
uint32_t number(const char* text, const std::string& option, uint32_t lo, uint32_t hi) {
    auto bad = [&] {
        usage(option + " expects a whole number in " + std::to_string(lo) + ".." + std::to_string(hi) + " (got '" + text + "')");
    };
    if (!std::isdigit(static_cast<unsigned char>(text[0]))) bad();
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::strtoull(text, &end, 10);
    if (*end || errno == ERANGE || v < lo || v > hi) bad();
    return uint32_t(v);
}

// A limit in 1..2^62, digits only.
uint64_t bigNumber(const char* text, const std::string& option) {
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::isdigit(static_cast<unsigned char>(text[0])) ? std::strtoull(text, &end, 10) : 0;
    if (!v || !end || *end || errno == ERANGE || v > (1ull << 62))
        usage(option + " expects a whole number in 1..2^62 (got '" + text + "')");
    return v;
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> const char* {
            if (i + 1 >= argc) usage(a + " needs a value");
            return argv[++i];
        };
        if (a == "--help" || a == "-h") {
            printUsage(stdout);
            std::exit(0);
        } else if (a == "--version") {
            std::printf("bricklight-render %s\n", BRICKLIGHT_VERSION_STRING);
            std::exit(0);
        } else if (a == "--scene") o.scene = value();
        else if (a == "--backend") o.backend = value();
        else if (a == "--width") o.width = number(value(), a, 1, 8192);
        else if (a == "--height") o.height = number(value(), a, 1, 8192);
        else if (a == "--frames") {
            o.frames = number(value(), a, 1, 100000);
            o.framesGiven = true;
        } else if (a == "--gi") {
            const std::string v = value();
            if (v == "sdf") o.gi = true;
            else if (v == "none") o.gi = false;
            else usage("--gi must be sdf or none (got '" + v + "')");
        } else if (a == "--gi-debug") {
            const std::string v = value();
            bool known = false;
            for (const char* n : kGiDebugNames) known = known || v == n;
            if (!known) usage("--gi-debug must be radiance-cache, irradiance-cache, probes, probe-sh, disocclusion or samples (got '" + v + "')");
            o.giDebug.push_back(v);
        } else if (a == "--gi-scale") {
            const uint32_t v = number(value(), a, 25, 100);
            using R = bricklight::gi::InternalResolution;
            if (v == 100) o.giScale = R::Native;
            else if (v == 75) o.giScale = R::Percent75;
            else if (v == 50) o.giScale = R::Percent50;
            else if (v == 25) o.giScale = R::Percent25;
            else usage("--gi-scale must be 100, 75, 50 or 25");
        }
        else if (a == "--spp") o.spp = number(value(), a, 1, 1u << 20);
        else if (a == "--reference") o.reference = true;
        else if (a == "--single-bounce") o.singleBounce = true;
        else if (a == "--validate") o.validate = true;
        else if (a == "--record") o.record = value();
        // Limits on model and texture files (examples/common/load_limits.h).
        else if (a == "--max-file-bytes") o.limits.maxFileBytes = bigNumber(value(), a);
        else if (a == "--max-json-bytes") o.limits.maxJsonBytes = bigNumber(value(), a);
        else if (a == "--max-json-depth") o.limits.maxJsonDepth = number(value(), a, 1, 1u << 20);
        else if (a == "--max-vertices") o.limits.maxVertices = bigNumber(value(), a);
        else if (a == "--max-indices") o.limits.maxIndices = bigNumber(value(), a);
        else if (a == "--max-face-indices") o.limits.maxFaceIndices = number(value(), a, 3, 1u << 20);
        else if (a == "--max-nodes") o.limits.maxNodes = bigNumber(value(), a);
        else if (a == "--max-node-depth") o.limits.maxNodeDepth = number(value(), a, 1, 1u << 20);
        else if (a == "--max-texture-pixels") o.limits.maxTexturePixels = bigNumber(value(), a);
        else if (a == "--allow-outside-paths") o.limits.allowOutsidePaths = true;
        else if (a == "--import-timeout") o.limits.importTimeoutSeconds = number(value(), a, 1, 86400);
        else if (a == "--import-memory") o.limits.importMemoryBytes = bigNumber(value(), a);
        else if (a == "--out") o.out = value();
        else if (a == "--exposure") {
            char* end = nullptr;
            const char* v = value();
            o.exposure = std::strtof(v, &end);
            if (!*v || *end || !(o.exposure > 0.0f) || !std::isfinite(o.exposure)) usage("--exposure expects a positive number");
        } else if (a == "--camera") {
            const char* v = value();
            char* end = nullptr;
            const char* at = v;
            for (int k = 0; k < 6; ++k) {
                o.camera[k] = std::strtof(at, &end);
                if (end == at || !std::isfinite(o.camera[k]) || (k < 5 && *end != ',') || (k == 5 && *end))
                    usage("--camera expects six numbers: EYE_X,EYE_Y,EYE_Z,AT_X,AT_Y,AT_Z (got '" + std::string(v) + "')");
                at = end + 1;
            }
            o.haveCamera = true;
        } else if (a == "--aov") {
            render::Aov aov;
            const std::string name = value();
            if (!render::aovFromName(name, &aov)) usage("unknown AOV '" + name + "'");
            o.aovs.push_back(aov);
        } else {
            usage("unknown option '" + a + "'");
        }
    }
    if (o.backend != "vulkan" && o.backend != "gl") usage("--backend must be vulkan or gl (got '" + o.backend + "')");
    if (!o.giDebug.empty() && (o.reference || !o.gi)) usage("--gi-debug needs the fast path with GI (not --reference or --gi none)");
    return o;
}

void progress(uint32_t done, uint32_t total) {
    if (!isatty(STDERR_FILENO)) return;
    const int width = 40, filled = int(double(done) / total * width);
    std::fprintf(stderr, "\r[%.*s%*s] %3u%% %u/%u spp", filled, "########################################", width - filled, "",
                 unsigned(100.0 * done / total), done, total);
    if (done == total) std::fprintf(stderr, "\n");
}

std::string stemOf(const std::string& out) {
    const size_t dot = out.find_last_of('.'), slash = out.find_last_of('/');
    return dot == std::string::npos || (slash != std::string::npos && dot < slash) ? out : out.substr(0, dot);
}
std::string aovPath(const std::string& out, render::Aov aov) { return stemOf(out) + "." + render::aovName(aov) + ".exr"; }
std::string giDebugPath(const std::string& out, const std::string& view) { return stemOf(out) + ".gi-" + view + ".exr"; }

// Every file the run will write, checked before any work: a bad path costs no render.
void checkOutputs(const Options& o) {
    std::vector<std::string> paths{o.out};
    for (render::Aov aov : o.aovs) paths.push_back(aovPath(o.out, aov));
    for (const std::string& view : o.giDebug) paths.push_back(giDebugPath(o.out, view));
    if (!o.record.empty()) paths.push_back(o.record);
    std::string error;
    for (const std::string& path : paths) {
        const size_t dot = path.find_last_of('.');
        const std::string ext = dot == std::string::npos ? "" : path.substr(dot);
        if (path != o.record && ext != ".png" && ext != ".exr")
            usage("'" + path + "': unsupported output format (use .png or .exr)");
        if (!render::checkOutputPath(path, &error)) usage(error);
    }
}

// Counts what the layers report during the run (the device, the validation wrapper, the SDF, GI): an error
// means the image may be wrong, so the run fails instead of writing it.
struct Reports {
    uint64_t errors = 0;
    std::string firstError;
    rhi::ErrorCallback callback() {
        return [this](rhi::Severity s, const std::string& m) {
            if (s == rhi::Severity::Info) return;
            std::fprintf(stderr, "bricklight-render: %s%s\n", s == rhi::Severity::Warning ? "warning: " : "", m.c_str());
            if (s == rhi::Severity::Error && errors++ == 0) firstError = m;
        };
    }
};

}  // namespace

int main(int argc, char** argv) {
    // A file-size limit (ulimit -f) or a full disk must make a write fail with an error, not kill us.
    signal(SIGXFSZ, SIG_IGN);
    const Options o = parse(argc, argv);
    checkOutputs(o);
    std::string error;
    scenes::SceneGeometry scene = scenes::loadScene(o.scene, &error, o.limits);
    if (scene.meshes.empty()) {
        std::fprintf(stderr, "bricklight-render: %s\n", error.empty() ? "the scene is empty" : error.c_str());
        return 1;
    }
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "bricklight-render: warning: %s\n", w.c_str());
    if (o.haveCamera) {
        scene.camera.eye = glm::vec3(o.camera[0], o.camera[1], o.camera[2]);
        scene.camera.at = glm::vec3(o.camera[3], o.camera[4], o.camera[5]);
    }
    Reports reports;
    const rhi::ErrorCallback report = reports.callback();
    // The layers, innermost first (each destroyed after the ones above it): the backend, the validation
    // wrapper (--validate), the recorder (--record).
    std::unique_ptr<rhi::IDevice> backendDevice, validationDevice;
    std::ofstream recordStream;
    std::string recordTemp;
    std::unique_ptr<rhi::IDevice> device;
    if (o.backend == "vulkan") {
        vulkan::DeviceOptions options;
        options.errorCallback = report;
        device = vulkan::createDevice(options);
    } else {
        device = gl::createHeadlessDevice(gl::HeadlessApi::Auto, report, &error);
    }
    if (!device) {
        std::fprintf(stderr, "bricklight-render: no %s device%s%s\n", o.backend.c_str(), error.empty() ? "" : ": ", error.c_str());
        return 1;
    }
    // --validate: the renderer, the SDF and GI talk to the backend through the validation wrapper, which
    // checks every record against its shader's reflection (messages go to the same report).
    if (o.validate) {
        backendDevice = std::move(device);
        device = rhi::createValidationDevice(*backendDevice);
        device->setErrorCallback(report);
    }
    // --record: every call of the render, as bricklight-replay reads it; written under a temporary name
    // and renamed when the run succeeds.
    if (!o.record.empty()) {
        recordTemp = o.record + ".tmp" + std::to_string(getpid());
        recordStream.open(recordTemp, std::ios::binary | std::ios::trunc);
        if (!recordStream) {
            std::fprintf(stderr, "bricklight-render: cannot write '%s': %s\n", recordTemp.c_str(), std::strerror(errno));
            return 1;
        }
        validationDevice = std::move(device);
        device = rhi::createRecordingDevice(*validationDevice, recordStream);
        device->setErrorCallback(report);
    }
    auto failRun = [&](const std::string& message) {
        std::fprintf(stderr, "bricklight-render: %s\n", message.c_str());
        if (!recordTemp.empty()) std::remove(recordTemp.c_str());
        return 1;
    };
    const auto start = std::chrono::steady_clock::now();
    if (o.reference && scene.animate) scene.animate(scene, o.frames - 1);  // the last frame's state
    std::unique_ptr<render::PathTracer> tracer;
    std::unique_ptr<render::RasterRenderer> raster;
    std::string how;
    if (o.reference) {
        render::PathTracerOptions pto;
        pto.width = o.width;
        pto.height = o.height;
        if (o.singleBounce) pto.maxBounces = 1;
        tracer = render::PathTracer::create(*device, scene, pto, &error);
        if (!tracer) return failRun(error);
        const uint32_t step = std::max(1u, std::min(o.spp, 16u));
        for (uint32_t done = 0; done < o.spp;) {
            const uint32_t n = std::min(step, o.spp - done);
            tracer->addSamples(n);
            device->endFrame();
            done += n;
            if (done < o.spp) device->waitIdle();  // progress reflects finished work
            progress(done, o.spp);
        }
        how = std::to_string(tracer->samples()) + " spp path-traced";
    } else {
        render::RasterOptions ro;
        ro.width = o.width;
        ro.height = o.height;
        ro.gi = o.gi;
        ro.giResolution = o.giScale;
        ro.giFeedback = !o.singleBounce;
        ro.errorCallback = report;  // the SDF's and GI's messages count as the device's do
        // GI converges over frames (each frame's light feeds the next): a still image gets 64 by default.
        const uint32_t frames = o.gi && !o.framesGiven && !scene.animate ? 64u : o.frames;
        raster = render::RasterRenderer::create(*device, scene, ro, &error);
        if (!raster) return failRun(error);
        for (uint32_t f = 0; f < frames; ++f) {
            if (f > 0 && scene.animate) {
                scene.animate(scene, f);
                if (!raster->setScene(scene, &error)) return failRun("frame " + std::to_string(f) + ": " + error);
            }
            raster->render();
            device->endFrame();
        }
        how = o.gi ? "rasterized, direct light + SDF GI over " + std::to_string(frames) + " frames"
                   : "rasterized, direct light only (" + std::to_string(ro.lightSamples) + " light samples per pixel)";
    }
    if (o.singleBounce) how += ", one bounce of indirect light";
    auto read = [&](render::Aov aov) { return tracer ? tracer->read(aov) : raster->read(aov); };
    render::Image combined = read(render::Aov::Combined);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (reports.errors)
        return failRun(std::to_string(reports.errors) + " error(s) were reported during the render (the first: " + reports.firstError +
                       "); the image may be wrong, so none was written");
    if (!render::writeImage(o.out, combined, o.exposure, &error)) return failRun(error);
    std::printf("wrote %s (%ux%u, %s, %u triangles, %s on %s) in %.2f s\n", o.out.c_str(), o.width, o.height,
                scene.name.c_str(), tracer ? tracer->triangleCount() : raster->triangleCount(), how.c_str(), o.backend.c_str(),
                seconds);
    for (const std::string& view : o.giDebug) {
        uint32_t mode = 0;
        while (view != kGiDebugNames[mode]) ++mode;
        render::Image img = raster->giDebugView(gi::DebugMode(mode), o.exposure);
        const std::string path = giDebugPath(o.out, view);
        if (img.rgb.empty() || !render::writeImage(path, img, 1.0f, &error))
            return failRun("the GI debug view " + view + " failed" + (error.empty() ? "" : ": " + error));
        std::printf("wrote %s\n", path.c_str());
    }
    for (render::Aov aov : o.aovs) {
        const std::string path = aovPath(o.out, aov);
        if (!render::writeImage(path, read(aov), 1.0f, &error)) return failRun(error);
        std::printf("wrote %s\n", path.c_str());
    }
    if (!o.record.empty()) {
        raster.reset();  // their resources' destruction is part of the recording
        tracer.reset();
        device.reset();  // the recorder's last lines
        recordStream.close();
        if (!recordStream || reports.errors || std::rename(recordTemp.c_str(), o.record.c_str()) != 0)
            return failRun("cannot write the recording '" + o.record + "'" + (reports.errors ? ": errors were reported" : ""));
        std::printf("wrote %s\n", o.record.c_str());
    }
    return 0;
}
