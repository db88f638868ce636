// bricklight-render: scene in, image out.
//
//   bricklight-render [--scene NAME|FILE] [--backend vulkan|gl] [--width W] [--height H] [--frames N]
//                     [--camera EX,EY,EZ,AX,AY,AZ] [--out FILE.png|.exr] [--aov NAME ...] [--reference --spp N]
//                     [--exposure E] [--gi sdf|vxgi|none] [--ao vxao|none] [--gi-scale 100|75|50|25] [--gi-debug VIEW ...]
//                     [--shadows bvh|shadowmap|hybrid] [--shadow-resolution N] [--shadow-lambda L] [--shadow-pcf R]
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

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bricklight/rhi_gl.h"
#include "bricklight/rhi_validation.h"
#include "bricklight/rhi_vulkan.h"
#include "bricklight/version.h"
#include "image_encoding.h"
#include "image_io.h"
#include "output_file.h"
#include "path_tracer.h"
#include "raster_renderer.h"
#include "render_options.h"
#include "scene_geometry.h"

using namespace bricklight;

namespace {

// The shared options (render_options.h: scene, camera, backend, size, techniques, limits) and the CLI's own.
struct Options : render::RenderOptions {
    uint32_t spp = 64;
    bool reference = false;
    std::string out = "out/render.png";
    std::vector<render::Aov> aovs;
    std::vector<std::string> giDebug;
    std::string record;  // --record: every device call of the render as JSON lines
};

const char* const kGiDebugNames[] = {"radiance-cache", "irradiance-cache", "probes", "probe-sh", "disocclusion", "samples"};
// Voxel cone tracing's views (vct::DebugMode, in its order), for --gi vxgi or --ao vxao.
const char* const kVctDebugNames[] = {"vct-opacity", "vct-emittance", "vct-level", "vct-rewritten"};
// The cone tracer's samples of the image's centre pixel (vct::ConeTracer::debugConeSamples).
const char* const kVctConeSamples = "vct-cone-samples";

// Hybrid reflections' views (--reflections hybrid): the denoised reflections and the classifier's tiles.
bool isReflectionDebug(const std::string& view) {
    render::View v;
    return render::viewFromName(view, &v) && render::viewIsReflection(v);
}

bool isVctDebug(const std::string& view) {
    for (const char* n : kVctDebugNames)
        if (view == n) return true;
    return view == kVctConeSamples;
}

void printUsage(FILE* to) {
    std::fprintf(to,
                 "usage: bricklight-render [options]\n%s"
                 "  [--out FILE.png|.%s] [--aov combined|direct|indirect-diffuse|albedo|normal|depth|ao ...]\n"
                 "  [--reference --spp N] [--gi-debug VIEW ...] [--record FILE.jsonl] [--help] [--version]\n"
                 "scenes: %s\n"
                 "exit status: 0 written; 1 the render failed; 2 usage error (docs/render.md)\n",
                 render::sharedOptionsUsage(), render::floatImageExtension(), scenes::builtinSceneNames());
}

[[noreturn]] void usage(const std::string& problem) {
    std::fprintf(stderr, "bricklight-render: %s\n", problem.c_str());
    printUsage(stderr);
    std::exit(2);
}

uint32_t number(const char* text, const std::string& option, uint32_t lo, uint32_t hi) {
    uint32_t v = 0;
    std::string error;
    if (!render::parseWholeNumber(text, option, lo, hi, &v, &error)) usage(error);
    return v;
}

Options parse(int argc, char** argv) {
    Options o;
    bool sppGiven = false;
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
        }
        std::string error;
        const render::OptionParse shared = render::parseSharedOption(argc, argv, i, o, &error);
        if (shared == render::OptionParse::Error) usage(error);
        if (shared == render::OptionParse::Consumed) continue;
        // --gi-debug and --aov take one or more values: every following argument up to the next option.
        auto values = [&]() {
            std::vector<std::string> list{value()};
            while (i + 1 < argc && argv[i + 1][0] != '-') list.push_back(argv[++i]);
            return list;
        };
        if (a == "--gi-debug") {
            for (const std::string& v : values()) {
                bool known = false;
                for (const char* n : kGiDebugNames) known = known || v == n;
                known = known || isVctDebug(v) || isReflectionDebug(v);
                if (!known)
                    usage("--gi-debug must be radiance-cache, irradiance-cache, probes, probe-sh, disocclusion or samples (the SDF GI's), "
                          "vct-opacity, vct-emittance, vct-level, vct-rewritten or vct-cone-samples (voxel cone tracing's) "
                          "or reflections, reflection-tile-class, reflection-rays or reflection-counters (hybrid reflections') (got '" + v + "')");
                if (std::find(o.giDebug.begin(), o.giDebug.end(), v) == o.giDebug.end()) o.giDebug.push_back(v);
            }
        }
        else if (a == "--spp") o.spp = number(value(), a, 1, 1u << 20), sppGiven = true;
        else if (a == "--reference") o.reference = true;
        else if (a == "--record") o.record = value();
        else if (a == "--out") o.out = value();
        else if (a == "--aov") {
            for (const std::string& name : values()) {
                render::Aov aov;
                if (!render::aovFromName(name, &aov))
                    usage("unknown AOV '" + name + "' (combined, direct, indirect-diffuse, albedo, normal, depth or ao)");
                if (std::find(o.aovs.begin(), o.aovs.end(), aov) == o.aovs.end()) o.aovs.push_back(aov);
            }
        } else {
            usage("unknown option '" + a + "'");
        }
    }
    std::string error;
    if (!render::checkSharedOptions(o, &error)) usage(error);
    if (sppGiven && !o.reference) usage("--spp sets the path tracer's samples: it needs --reference");
    if (o.reference && o.shadows != render::ShadowMode::Bvh)
        usage("--shadows shadowmap and hybrid need the fast path (not --reference, whose visibility is exact)");
    const bool vct = o.vxao || (o.gi && o.giTechnique == render::GiTechnique::Vct);
    for (const std::string& view : o.giDebug) {
        if (o.reference) usage("--gi-debug needs the fast path (not --reference)");
        if (isVctDebug(view) && !vct) usage("--gi-debug " + view + " needs voxel cone tracing (--gi vxgi or --ao vxao)");
        if (isReflectionDebug(view) && o.reflections != render::ReflectionMode::Hybrid)
            usage("--gi-debug " + view + " needs hybrid reflections (--reflections hybrid)");
        if (!isVctDebug(view) && !(o.gi && o.giTechnique == render::GiTechnique::Sdf))
            usage("--gi-debug " + view + " needs the SDF GI (--gi sdf, the default)");
    }
    for (render::Aov aov : o.aovs)
        if (aov == render::Aov::Ao && !o.reference && !vct)
            usage("--aov ao needs --reference (the path tracer's) or voxel cone tracing (--ao vxao or --gi vxgi)");
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
    const size_t dot = out.find_last_of('.'), slash = out.find_last_of(render::pathSeparators());
    return dot == std::string::npos || (slash != std::string::npos && dot < slash) ? out : out.substr(0, dot);
}
// AOVs and debug views are linear: .exr (.hdr in a build whose image files are stb's, e.g. on Windows).
std::string aovPath(const std::string& out, render::Aov aov) {
    return stemOf(out) + "." + render::aovName(aov) + "." + render::floatImageExtension();
}
std::string giDebugPath(const std::string& out, const std::string& view) {
    return stemOf(out) + ".gi-" + view + "." + render::floatImageExtension();
}

// Every file the run will write, checked before any work: a bad path costs no render.
void checkOutputs(const Options& o) {
    std::vector<std::pair<std::string, std::string>> paths{{o.out, "--out"}};  // path, what writes it
    for (render::Aov aov : o.aovs) paths.push_back({aovPath(o.out, aov), std::string("--aov ") + render::aovName(aov)});
    for (const std::string& view : o.giDebug) paths.push_back({giDebugPath(o.out, view), "--gi-debug " + view});
    if (!o.record.empty()) paths.push_back({o.record, "--record"});
    std::string error;
    for (const auto& [path, what] : paths) {
        if (what != "--record" && !render::isWritableImageExtension(render::imageExtension(path)))
            usage("'" + path + "': unsupported output format " + render::writableImageFormats());
        if (!render::checkOutputPath(path, &error)) usage(error);
    }
    // Two outputs on one file: the second would overwrite the first (a recording where the image should be).
    for (size_t i = 0; i < paths.size(); ++i)
        for (size_t j = i + 1; j < paths.size(); ++j) {
            std::error_code ec1, ec2;
            const auto a = std::filesystem::weakly_canonical(paths[i].first, ec1), b = std::filesystem::weakly_canonical(paths[j].first, ec2);
            if (ec1 || ec2 ? paths[i].first == paths[j].first : a == b)
                usage(paths[i].second + " and " + paths[j].second + " name the same file ('" + paths[j].first + "'): give each its own");
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
#if defined(SIGXFSZ)
    // A file-size limit (ulimit -f) or a full disk must make a write fail with an error, not kill us.
    signal(SIGXFSZ, SIG_IGN);
#endif
    const Options o = parse(argc, argv);
    checkOutputs(o);
    std::string error;
    scenes::SceneGeometry scene = render::loadSceneOf(o, &error);
    if (scene.meshes.empty()) {
        std::fprintf(stderr, "bricklight-render: %s\n", error.c_str());
        return 1;
    }
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "bricklight-render: warning: %s\n", w.c_str());
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
    // Work a CPU driver's loop limit cut short is wrong, not missing: say so, with the count.
    auto warnCutShort = [](uint64_t cut, uint64_t of, const char* what) {
        if (cut)
            std::fprintf(stderr,
                         "bricklight-render: warning: %llu of %llu %s were cut short by the driver's limit on loop iterations "
                         "(CPU drivers end a shader's loops after 65,535 iterations in all): the image is wrong where a ray crosses "
                         "that many overlapping triangles\n",
                         (unsigned long long)cut, (unsigned long long)of, what);
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
        warnCutShort(tracer->samplesCutShort(), uint64_t(tracer->samples()) * o.width * o.height, "samples");
        if (const uint64_t nonFinite = tracer->samplesNonFinite())
            std::fprintf(stderr,
                         "bricklight-render: warning: %llu of %llu samples came out infinite or NaN and were left out of the image "
                         "(a pixel's mean is over its finite samples)\n",
                         (unsigned long long)nonFinite, (unsigned long long)tracer->samples() * o.width * o.height);
    } else {
        render::RasterOptions ro = render::rasterOptionsOf(o);
        ro.errorCallback = report;  // the SDF's and GI's messages count as the device's do
        const uint32_t frames = render::framesToRender(o, scene);
        raster = render::RasterRenderer::create(*device, scene, ro, &error);
        if (!raster) return failRun(error);
        for (uint32_t f = 0; f < frames; ++f) {
            if (!render::animateTo(scene, *raster, f, &error)) return failRun(error);
            raster->render();
            device->endFrame();
        }
        warnCutShort(raster->invocationsCutShort(), uint64_t(frames) * o.width * o.height, "pixel shadings (pixels x frames; fragments of glass and voxelization count too)");
        if (gi::GiContext* giContext = raster->giContext())
            if (const uint64_t bound = giContext->raysAtAlphaBound())
                std::fprintf(stderr,
                             "bricklight-render: warning: %llu GI rays through foliage passed as many cut-out cards as they may (6) and took "
                             "the next one as opaque: the indirect light there is too dark (docs/gi.md, Foliage)\n",
                             (unsigned long long)bound);
        const std::string technique = o.giTechnique == render::GiTechnique::Vct ? "voxel cone tracing"
                                      : o.giUnseenFromVct                         ? "SDF GI (unseen surfaces from a clip-map)"
                                                                                  : "SDF GI";
        how = o.gi ? "rasterized, direct light + " + technique + " over " + std::to_string(frames) + " frames"
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
        render::Image img;
        uint32_t mode = 0;
        render::View reflectionView;
        if (isReflectionDebug(view) && render::viewFromName(view, &reflectionView)) {
            img = raster->reflectionView(reflectionView);
        } else if (view == kVctConeSamples) {
            img = raster->vctConeSamplesView();
        } else if (isVctDebug(view)) {
            while (view != kVctDebugNames[mode]) ++mode;
            img = raster->vctDebugView(vct::DebugMode(mode), o.exposure);
        } else {
            while (view != kGiDebugNames[mode]) ++mode;
            img = raster->giDebugView(gi::DebugMode(mode), o.exposure);
        }
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
        std::string why = !recordStream ? "the write failed" : reports.errors ? "errors were reported" : "";
        if (why.empty()) render::replaceFile(recordTemp, o.record, &why);
        if (!why.empty()) return failRun("cannot write the recording '" + o.record + "': " + why);
        std::printf("wrote %s\n", o.record.c_str());
    }
    return 0;
}
