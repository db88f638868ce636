// bricklight-viewer: the renderer bricklight-render drives, in a window (GLFW + Dear ImGui), on Vulkan (our
// backend embedded in the viewer's own device and swapchain) or OpenGL 4.5 (on the window's context).
//
//   bricklight-viewer [the options bricklight-render shares: --scene, --backend, --camera, --gi, ...]
//                     [--window WxH] [--view NAME] [--pip NAME] [--no-vsync] [--fps-limit N]
//                     [--screenshot FILE.png] [--exit-after N] [--screenshot-dir DIR] [--hidden] [--log]
//                     [--open-panels] [--help] [--version]
//
// --width/--height fix the render size (scaled to the window); without them the render follows the
// window. --frames N renders N frames and exits (with --screenshot: writes the view first), as
// bricklight-render renders N frames, so that both programs give the same image for the same options.
// Exit status: 0 done; 1 failed (no display, no device, a reported error, a failed write); 2 usage error.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bricklight/version.h"
#include "render_options.h"
#include "viewer_app.h"

using namespace bricklight;

namespace {

void printUsage(FILE* to) {
    std::fprintf(to,
                 "usage: bricklight-viewer [options]\n%s"
                 "  [--window WxH] [--view NAME] [--pip NAME] [--no-vsync] [--fps-limit N]\n"
                 "  [--screenshot FILE.png] [--exit-after N] [--screenshot-dir DIR] [--hidden] [--log]\n"
                 "  [--open-panels] [--help] [--version]\n"
                 "scenes: %s\n"
                 "views: final, direct, indirect-diffuse, specular-gi, albedo, normal, depth, motion, sdf-distance,\n"
                 "  sdf-normal, sdf-iterations, sdf-brick-id, sdf-cascade-id, sdf-uvw, gi-radiance-cache,\n"
                 "  gi-irradiance-cache, gi-probes, gi-probe-sh, gi-disocclusion, gi-samples\n"
                 "keys: WASD QE move, right mouse look, scroll speed, Tab orbit, 1-4 bookmarks, G GI, V/B view,\n"
                 "  P picture-in-picture, Space pause, F12 screenshot, F1 panel, Esc quit (docs/viewer.md)\n"
                 "exit status: 0 done; 1 failed; 2 usage error\n",
                 render::sharedOptionsUsage(), scenes::builtinSceneNames());
}

[[noreturn]] void usage(const std::string& problem) {
    std::fprintf(stderr, "bricklight-viewer: %s\n", problem.c_str());
    printUsage(stderr);
    std::exit(2);
}

render::View view(const std::string& name) {
    render::View v;
    if (!render::viewFromName(name, &v)) usage("unknown view '" + name + "' (see --help)");
    return v;
}

viewer::ViewerSettings parse(int argc, char** argv) {
    viewer::ViewerSettings s;
    bool widthGiven = false, heightGiven = false;
    uint32_t exitAfter = 0;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> const char* {
            if (i + 1 >= argc) usage(a + " needs a value");
            return argv[++i];
        };
        auto whole = [&](uint32_t lo, uint32_t hi) {
            uint32_t v = 0;
            std::string error;
            if (!render::parseWholeNumber(value(), a, lo, hi, &v, &error)) usage(error);
            return v;
        };
        if (a == "--help" || a == "-h") {
            printUsage(stdout);
            std::exit(0);
        }
        if (a == "--version") {
            std::printf("bricklight-viewer %s\n", BRICKLIGHT_VERSION_STRING);
            std::exit(0);
        }
        widthGiven = widthGiven || a == "--width";
        heightGiven = heightGiven || a == "--height";
        std::string error;
        const render::OptionParse shared = render::parseSharedOption(argc, argv, i, s.render, &error);
        if (shared == render::OptionParse::Error) usage(error);
        if (shared == render::OptionParse::Consumed) continue;
        if (a == "--window") {
            const std::string v = value();
            const size_t x = v.find('x');
            uint32_t w = 0, h = 0;
            if (x == std::string::npos || !render::parseWholeNumber(v.substr(0, x).c_str(), a, 64, 8192, &w, &error) ||
                !render::parseWholeNumber(v.substr(x + 1).c_str(), a, 64, 8192, &h, &error))
                usage("--window expects WxH, each 64..8192 (got '" + v + "')");
            s.windowWidth = w;
            s.windowHeight = h;
        } else if (a == "--view") s.view = view(value());
        else if (a == "--pip") {
            s.pipView = view(value());
            s.pip = true;
        } else if (a == "--no-vsync") s.vsync = false;
        else if (a == "--fps-limit") s.fpsLimit = whole(1, 1000);
        else if (a == "--screenshot") s.screenshot = value();
        else if (a == "--screenshot-dir") s.screenshotDir = value();
        else if (a == "--exit-after") exitAfter = whole(1, 100000000);
        else if (a == "--hidden") s.hidden = true;
        else if (a == "--log") s.log = true;
        else if (a == "--open-panels") s.openPanels = true;
        else usage("unknown option '" + a + "'");
    }
    std::string error;
    if (!render::checkSharedOptions(s.render, &error)) usage(error);
    if (widthGiven != heightGiven) usage("--width and --height go together (the render size; without both it follows the window)");
    s.fixedSize = widthGiven;
    if (s.render.framesGiven && exitAfter) usage("--frames and --exit-after are the same: give one");
    s.exitAfterFrames = s.render.framesGiven ? s.render.frames : exitAfter;
    if (!s.screenshot.empty() && !s.exitAfterFrames) usage("--screenshot needs --frames N (the frame to write)");
    if (!s.screenshot.empty() && s.screenshot.size() < 4) usage("--screenshot expects a .png file");
    if (!s.screenshot.empty() && s.screenshot.substr(s.screenshot.size() - 4) != ".png") usage("--screenshot expects a .png file");
    if (!s.render.gi && (render::viewNeedsGi(s.view) || (s.pip && render::viewNeedsGi(s.pipView))))
        usage("that view needs GI (not --gi none)");
    return s;
}

}  // namespace

int main(int argc, char** argv) { return viewer::ViewerApp::run(parse(argc, argv)); }
