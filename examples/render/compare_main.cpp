// bricklight-compare A B: how far image A is from the reference B (PNG, EXR or anything OpenImageIO reads).
//
//   bricklight-compare A B [--max-relmse X]
//
// Prints relMSE (epsilon 0.01), RMSE, PSNR, SSIM of display luminance and grain (docs/render.md). Exit status: 0
// compared (and within --max-relmse); 1 not: relMSE over X, an image that cannot be read (bounded as every
// image file we read: render::readImage), sizes that differ, or a value that is not finite in either image
// (NaN or infinite: no figure would mean anything); 2 a usage error. --help, --version.
#include <cmath>
#include <cstdio>
#include <new>
#include <cstdlib>
#include <string>

#include "bricklight/version.h"
#include "image_io.h"
#include "image_metrics.h"

using namespace bricklight;

int main(int argc, char** argv) {
    std::string a, b;
    double maxRelMse = -1.0;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::printf("usage: bricklight-compare A B [--max-relmse X]   (B is the reference)\n"
                        "exit status: 0 compared (within X); 1 over X, an image cannot be read, the sizes differ\n"
                        "             or a value is not finite (NaN, infinite); 2 usage error\n");
            return 0;
        }
        if (arg == "--version") {
            std::printf("bricklight-compare %s\n", BRICKLIGHT_VERSION_STRING);
            return 0;
        }
        if (arg == "--max-relmse") {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "bricklight-compare: --max-relmse needs a value\n");
                return 2;
            }
            char* end = nullptr;
            maxRelMse = std::strtod(argv[++i], &end);
            if (end == argv[i] || *end || !(maxRelMse >= 0.0) || !std::isfinite(maxRelMse)) {
                std::fprintf(stderr, "bricklight-compare: --max-relmse expects a number >= 0\n");
                return 2;
            }
        } else if (arg.size() > 1 && arg[0] == '-') {
            std::fprintf(stderr, "bricklight-compare: unknown option '%s'\nusage: bricklight-compare A B [--max-relmse X]\n", arg.c_str());
            return 2;
        } else if (a.empty()) {
            a = arg;
        } else if (b.empty()) {
            b = arg;
        } else {
            std::fprintf(stderr, "bricklight-compare: unexpected argument '%s'\nusage: bricklight-compare A B [--max-relmse X]\n", arg.c_str());
            return 2;
        }
    }
    if (b.empty()) {
        std::fprintf(stderr, "usage: bricklight-compare A B [--max-relmse X]   (B is the reference)\n");
        return 2;
    }
    render::Image ia, ib;
    std::string error;
    try {
        if (!render::readImage(a, &ia, &error) || !render::readImage(b, &ib, &error)) {
            std::fprintf(stderr, "bricklight-compare: %s\n", error.c_str());
            return 1;
        }
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "bricklight-compare: out of memory reading the images\n");
        return 1;
    }
    if (ia.width != ib.width || ia.height != ib.height) {
        std::fprintf(stderr, "bricklight-compare: sizes differ: %ux%u vs %ux%u\n", ia.width, ia.height, ib.width, ib.height);
        return 1;
    }
    // A NaN or an infinity makes every figure NaN or meaningless: not a comparison that passed.
    auto finite = [](const std::string& name, const render::Image& image) {
        size_t bad = 0;
        for (float v : image.rgb) bad += !std::isfinite(v);
        if (bad)
            std::fprintf(stderr, "bricklight-compare: '%s' holds %zu values that are not finite (NaN or infinite) of %zu\n", name.c_str(), bad,
                         image.rgb.size());
        return bad == 0;
    };
    const bool finiteA = finite(a, ia), finiteB = finite(b, ib);
    if (!finiteA || !finiteB) return 1;
    const render::ImageMetrics m = render::compareImages(ia, ib);
    std::printf("relMSE %.6g (eps %.2g)  RMSE %.6g  PSNR %.2f dB  SSIM %.4f  mean %.6g vs %.6g  grain %.4g vs %.4g (%.3fx)\n",
                m.relMse, render::kRelMseEpsilon, m.rmse, m.psnr, m.ssim, m.meanA, m.meanB, m.grainA, m.grainB,
                m.grainB > 0.0 ? m.grainA / m.grainB : 0.0);
    return maxRelMse >= 0.0 && m.relMse > maxRelMse ? 1 : 0;
}
