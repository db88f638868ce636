// bricklight-render: scene in, image out.
//
//   bricklight-render [--scene NAME|FILE] [--backend vulkan|gl] [--width W] [--height H] [--frames N]
//                     [--camera EX,EY,EZ,AX,AY,AZ] [--out FILE.png|.exr] [--aov NAME ...] [--reference --spp N]
//                     [--exposure E] [--gi sdf|none] [--gi-scale 100|75|50|25] [--gi-debug VIEW ...]
//                     [--single-bounce]
//
// Without --reference: a rasterized G-buffer, direct lighting and GI from the sparse brick distance field
// (--gi sdf, the default; over --frames frames the bounces accumulate); with it, the path tracer (the
// ground truth). AOVs go next to --out as <stem>.<aov>.exr (linear float). --single-bounce keeps indirect
// light to one bounce on both paths (the path tracer stops after one; GI is fed direct light only), to
// measure GI's gather apart from its multi-bounce feedback. See docs/render.md.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "bricklight/rhi_gl.h"
#include "bricklight/rhi_validation.h"
#include "bricklight/rhi_vulkan.h"
#include "image_io.h"
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
};

const char* const kGiDebugNames[] = {"radiance-cache", "irradiance-cache", "probes", "probe-sh", "disocclusion", "samples"};

[[noreturn]] void usage(const std::string& problem) {
    std::fprintf(stderr, "bricklight-render: %s\n", problem.c_str());
    std::fprintf(stderr,
                 "usage: bricklight-render [--scene NAME|FILE] [--backend vulkan|gl] [--width W] [--height H]\n"
                 "                         [--frames N] [--camera EX,EY,EZ,AX,AY,AZ] [--out FILE.png|.exr]\n"
                 "                         [--aov combined|direct|indirect-diffuse|albedo|normal|depth ...]\n"
                 "                         [--reference --spp N] [--exposure E] [--gi sdf|none]\n"
                 "                         [--gi-scale 100|75|50|25] [--gi-debug VIEW ...] [--single-bounce]\n"
                 "                         [--validate]\n"
                 "scenes: %s\n", scenes::builtinSceneNames());
    std::exit(2);
}

uint32_t number(const char* text, const std::string& option, uint32_t lo, uint32_t hi) {
    char* end = nullptr;
    const unsigned long v = std::strtoul(text, &end, 10);
    if (!*text || *end || v < lo || v > hi)
        usage(option + " expects a whole number in " + std::to_string(lo) + ".." + std::to_string(hi) + " (got '" + text + "')");
    return uint32_t(v);
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> const char* {
            if (i + 1 >= argc) usage(a + " needs a value");
            return argv[++i];
        };
        if (a == "--scene") o.scene = value();
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
    return o;
}

void progress(uint32_t done, uint32_t total) {
    if (!isatty(STDERR_FILENO)) return;
    const int width = 40, filled = int(double(done) / total * width);
    std::fprintf(stderr, "\r[%.*s%*s] %3u%% %u/%u spp", filled, "########################################", width - filled, "",
                 unsigned(100.0 * done / total), done, total);
    if (done == total) std::fprintf(stderr, "\n");
}

std::string aovPath(const std::string& out, render::Aov aov) {
    const size_t dot = out.find_last_of('.'), slash = out.find_last_of('/');
    const std::string stem = dot == std::string::npos || (slash != std::string::npos && dot < slash) ? out : out.substr(0, dot);
    return stem + "." + render::aovName(aov) + ".exr";
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parse(argc, argv);
    std::string error;
    scenes::SceneGeometry scene = scenes::loadScene(o.scene, &error);
    if (scene.meshes.empty()) {
        std::fprintf(stderr, "bricklight-render: %s\n", error.empty() ? "the scene is empty" : error.c_str());
        return 1;
    }
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "bricklight-render: warning: %s\n", w.c_str());
    if (o.haveCamera) {
        scene.camera.eye = glm::vec3(o.camera[0], o.camera[1], o.camera[2]);
        scene.camera.at = glm::vec3(o.camera[3], o.camera[4], o.camera[5]);
    }
    rhi::ErrorCallback report = [](rhi::Severity s, const std::string& m) {
        if (s != rhi::Severity::Info) std::fprintf(stderr, "bricklight-render: %s\n", m.c_str());
    };
    std::unique_ptr<rhi::IDevice> backendDevice;  // with --validate, under `device` (destroyed after it)
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
        if (!tracer) {
            std::fprintf(stderr, "bricklight-render: %s\n", error.c_str());
            return 1;
        }
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
        // GI converges over frames (each frame's light feeds the next): a still image gets 64 by default.
        const uint32_t frames = o.gi && !o.framesGiven && !scene.animate ? 64u : o.frames;
        raster = render::RasterRenderer::create(*device, scene, ro, &error);
        if (!raster) {
            std::fprintf(stderr, "bricklight-render: %s\n", error.c_str());
            return 1;
        }
        for (uint32_t f = 0; f < frames; ++f) {
            if (f > 0 && scene.animate) {
                scene.animate(scene, f);
                if (!raster->setScene(scene, &error)) {
                    std::fprintf(stderr, "bricklight-render: frame %u: %s\n", f, error.c_str());
                    return 1;
                }
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
    if (!render::writeImage(o.out, combined, o.exposure, &error)) {
        std::fprintf(stderr, "bricklight-render: %s\n", error.c_str());
        return 1;
    }
    std::printf("wrote %s (%ux%u, %s, %u triangles, %s on %s) in %.2f s\n", o.out.c_str(), o.width, o.height,
                scene.name.c_str(), tracer ? tracer->triangleCount() : raster->triangleCount(), how.c_str(), o.backend.c_str(),
                seconds);
    for (const std::string& view : o.giDebug) {
        if (!raster) usage("--gi-debug needs the fast path with GI (not --reference or --gi none)");
        uint32_t mode = 0;
        while (view != kGiDebugNames[mode]) ++mode;
        render::Image img = raster->giDebugView(gi::DebugMode(mode), o.exposure);
        const size_t dot = o.out.find_last_of('.');
        const std::string path = (dot == std::string::npos ? o.out : o.out.substr(0, dot)) + ".gi-" + view + ".exr";
        if (img.rgb.empty() || !render::writeImage(path, img, 1.0f, &error)) {
            std::fprintf(stderr, "bricklight-render: the GI debug view %s failed%s%s\n", view.c_str(), error.empty() ? "" : ": ", error.c_str());
            return 1;
        }
        std::printf("wrote %s\n", path.c_str());
    }
    for (render::Aov aov : o.aovs) {
        const std::string path = aovPath(o.out, aov);
        if (!render::writeImage(path, read(aov), 1.0f, &error)) {
            std::fprintf(stderr, "bricklight-render: %s\n", error.c_str());
            return 1;
        }
        std::printf("wrote %s\n", path.c_str());
    }
    return 0;
}
