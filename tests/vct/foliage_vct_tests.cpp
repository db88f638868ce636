// Voxel cone tracing's three ways with the foliage scene's alpha-tested cards (RasterOptions::foliage: coverage-
// weighted voxels, cards voxelized solid, cards left out of the voxels) against the path tracer's indirect
// diffuse, over the whole image and over the grass pixels, with the sun behind the camera (the scene's) and
// turned round (behind the cards). Figures are printed (WARN) for docs/vct.md, "Foliage".
#include <chrono>

#include "backend_test.h"
#include "foliage_test_support.h"
#include "image_metrics.h"
#include "path_tracer.h"
#include "raster_renderer.h"
#include "reference_cache.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

void vctFoliageVariants(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const auto start = std::chrono::steady_clock::now();
    // One bounce (bounces off: the clip-map is voxelized once and kept), against the path tracer's one bounce:
    // converged after the first frame (16 frames differ from 2 by < 1 %); 6 frames give every pixel of the
    // sparse tracing's 2 × 2 blocks its cones. 32 spp: relMSE 0.005 against 256 spp, far below the differences
    // measured here. With bounces each frame revoxelizes the whole scene (~10 s a frame on lavapipe) and the
    // light climbs one bounce a frame.
    constexpr uint32_t kSize = 64, kFrames = 6, kSpp = 32;
    for (bool backLit : {false, true}) {
        const scenes::SceneGeometry s = foliageScene(backLit);
        auto reference = pathTraced(td, s, kSize, kSpp, true, 1, 1);
        size_t grassPixels = 0;
        const std::vector<uint8_t> grass = grassMask(reference.read(render::Aov::Albedo), &grassPixels);
        REQUIRE(grassPixels > kSize * kSize / 8);
        render::RasterOptions o;
        o.width = o.height = kSize;
        o.gi = true;
        o.giTechnique = render::GiTechnique::Vct;
        o.giFeedback = false;
        FoliageFigures f[3];
        foliageVariants(td, s, o, kFrames, reference.read(render::Aov::IndirectDiffuse), grass, 1u, 4,
                        backend + (backLit ? ", sun behind the cards" : ", sun behind the camera"), f);
        // Since a voxel sends the coverage-weighted mean of surfaces that cover one another in projection instead
        // of their sum (resolve_light.comp), no variant is far off: whole-image means 1.2–2.6 × the reference's
        // (before, 3.7–5.1 ×, the ground's and the tufts' light summed over every surface in a voxel).
        for (const FoliageFigures& v : f) CHECK(v.whole.meanA < 3.0 * v.whole.meanB);
        // Alpha-aware (measured: whole relMSE 0.049 / 0.057, mean 1.58 / 1.60 × with the sun behind the camera /
        // the cards; grass 0.084 / 0.106, 1.64 / 1.66 ×; before voxels sent the light their opacity takes, 0.096 /
        // 0.155, 1.85 / 2.05 ×). It is closer than the cards left out on the mean in both lightings (error 0.58
        // against 1.75; 0.60 against 1.26) and on relMSE with the sun behind the camera.
        CHECK(f[0].whole.relMse < (backLit ? 0.2 : 0.13));
        CHECK(f[0].whole.meanA < (backLit ? 2.3 : 2.1) * f[0].whole.meanB);
        CHECK(meanError(f[0].whole) < 0.95 * meanError(f[2].whole));
        if (!backLit) CHECK(f[0].whole.relMse < 0.6 * f[2].whole.relMse);
        // The solid cards are the closest (whole relMSE 0.034 / 0.045, mean 1.36 / 1.44 ×): their over-occlusion
        // offsets what the alpha-aware voxels still under-occlude — a voxel's opacity is the largest any card in it
        // writes, not their union, so dense grass finer than a voxel lets cones through (docs/vct.md, *Foliage*).
        // Not asserted either way: it is the next cause to remove, not a property to keep.
        // The voxels' words are deterministic (no frame in the coverage points or the emittance's seed); what moves
        // is the sparse tracing's pixel of each 2 × 2 block and the history.
        CHECK(f[0].flicker < 0.03);
    }
    WARN(backend << ": " << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s");
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("foliage: voxel cone tracing's alpha-aware cards against built-opaque and left-out ones, and the path tracer", "[vct]",
             vctFoliageVariants)
