// GI (gi::GiContext through the renderer's fast path) against the path tracer, across backends, over
// time, and on bad input. Bounds are stated where they are asserted; docs/gi.md lists the figures.
#include <cmath>
#include <sstream>

#include "backend_test.h"
#include "image_metrics.h"
#include "path_tracer.h"
#include "raster_renderer.h"
#include "reference_cache.h"
#include "shared_references.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

constexpr uint32_t kSize = 64;
constexpr uint32_t kCornellSize = kSharedReferenceSize;  // the Cornell comparison at the size (128)

std::unique_ptr<render::RasterRenderer> giRenderer(TestDevice& td, const scenes::SceneGeometry& scene, uint32_t size = kSize,
                                                   bool relight = true, uint32_t cacheBricks = 0, uint32_t injectTile = 0,
                                                   uint32_t probeTile = 0, bool feedback = true) {
    render::RasterOptions o;
    o.width = o.height = size;
    o.gi = true;
    o.giRelight = relight;
    o.giFeedback = feedback;
    o.giCacheBricks = cacheBricks;
    o.giInjectTile = injectTile;
    o.giProbeTile = probeTile;
    std::string error;
    auto r = render::RasterRenderer::create(*td.device, scene, o, &error);
    INFO(error);
    REQUIRE(r);
    return r;
}

// The message of a context that `cd` (32×32 display) must not create; the context's own report is silenced.
std::string refusal(TestDevice& td, sdf::SdfScene& scene, gi::ContextDesc cd) {
    cd.displayWidth = cd.displayHeight = 32;
    cd.errorCallback = [](rhi::Severity, const std::string&) {};
    Error error;
    CHECK_FALSE(gi::GiContext::create(*td.device, scene, cd, &error));
    return error.message;
}

// Renders n frames and returns the mean of the last `averaged` frames' image of `aov`. The GI's passes race
// where threads blend into the same cache texel (last writer wins), so one frame's image carries noise that
// depends on the driver's thread schedule; a mean over frames measures the light the GI converged to.
render::Image averagedFrames(TestDevice& td, render::RasterRenderer& r, uint32_t n, uint32_t averaged,
                             render::Aov aov) {
    frames(td, r, n - averaged);
    render::Image sum;
    for (uint32_t f = 0; f < averaged; ++f) {
        frames(td, r, 1);
        const render::Image img = r.read(aov);
        if (sum.rgb.empty()) sum = render::Image{img.width, img.height, std::vector<float>(img.rgb.size(), 0.0f)};
        for (size_t i = 0; i < img.rgb.size(); ++i) sum.rgb[i] += img.rgb[i] / float(averaged);
    }
    return sum;
}

void cornellAgainstReference(const std::string& backend) {
    // 64 frames of GI (each frame's lit image feeds the next: multi-bounce) against 512 spp of the path
    // tracer, 128². Measured (lavapipe and llvmpipe, against 1024 spp): indirect relMSE 0.0046, mean 0.0440 vs
    // 0.0479 (92 %; 95 % at 120 frames) since probe rays light the surfaces no view has lit
    // (DispatchDesc::lightUnseenSurfaces); before, relMSE 0.027, mean 0.0326 (68 %). The bounds sit about
    // twice the measured distance from perfect (the 512-spp reference's own noise included).
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    auto gi = giRenderer(td, cornell, kCornellSize);
    frames(td, *gi, 64);
    auto reference = cornellReference(td);
    const render::Image indirect = gi->read(render::Aov::IndirectDiffuse);
    const render::Image refIndirect = reference.read(render::Aov::IndirectDiffuse);
    REQUIRE(allFinite(indirect.rgb));
    checkAgainstReference("indirect-diffuse", indirect, refIndirect, {.relMse = 0.015, .ssim = 0.7, .minMean = 0.84, .maxMean = 1.1});
    checkAgainstReference("combined", gi->read(render::Aov::Combined), reference.read(render::Aov::Combined), {.relMse = 0.012, .ssim = 0.85});
    // GI adds light: the composite is brighter than direct light alone.
    CHECK(imageMean(gi->read(render::Aov::Combined)) > 1.1 * imageMean(gi->read(render::Aov::Direct)));
    REQUIRE_NO_MESSAGES(td);
}

void cornellSingleBounceAgainstReference(const std::string& backend) {
    // GI's gather alone, without its multi-bounce feedback: GI fed direct light only (RasterOptions::
    // giFeedback false) against the path tracer stopped after one bounce (maxBounces 1), the Cornell box,
    // 128², 64 frames against 512 spp (the one-bounce reference voxel cone tracing's test compares with too,
    // traced once: reference_cache.h; measured against 1024 spp): relMSE 0.0025, mean 0.0248 vs 0.0241 (103 %).
    // The rays that meet surfaces the camera never saw (behind the blocks) light them from the field's material
    // and the lamp, one bounce only (DispatchDesc::relightBounces false). Before that, their stand-in (the light
    // of the neighbouring directions) gave 89 % (relMSE 0.0096); the probe's mean alone 84 %; such hits black,
    // 67 %. The multi-bounce result compounds a loss bounce after bounce, so this test pins the first bounce on
    // its own.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    auto gi = giRenderer(td, cornell, kCornellSize, true, 0, 0, 0, /*feedback*/ false);
    frames(td, *gi, 64);
    auto reference = cornellOneBounceReference(td);
    const render::Image indirect = gi->read(render::Aov::IndirectDiffuse);
    REQUIRE(allFinite(indirect.rgb));
    checkAgainstReference("single bounce: indirect-diffuse", indirect, reference.read(render::Aov::IndirectDiffuse),
                          {.relMse = 0.008, .ssim = 0.7, .minMean = 0.93, .maxMean = 1.1});
    // Fed direct light only, GI still adds light to the composite.
    CHECK(imageMean(gi->read(render::Aov::Combined)) > 1.1 * imageMean(gi->read(render::Aov::Direct)));
    REQUIRE_NO_MESSAGES(td);
}

void corridorAgainstReference(const std::string& backend) {
    // Issue 36's thin walls: the built-in corridor, an L of single-sided walls (no thickness) lit by one lamp around
    // the corner from the camera, so nearly all the light on screen has bounced among surfaces the camera never saw
    // (the path tracer's one bounce is a tenth of it). 96 × 64, 120 frames, against 1024 spp. Measured: indirect mean
    // 98.5 % (llvmpipe 103.4 %), relMSE 0.041 (0.052) since the probes' reprojection moves carried hits and marks the
    // texels whose light may lie in another direction from the new probe (reproject_probes.comp), traced in their
    // block's turn or emptied (fill_probes_body.glsl); 89.5 % before the marks, 26 % before probe rays followed a path
    // through the never-seen surfaces. Not converged at 120 frames: 81 % at 480 (docs/gi.md, Known limitations). Bounds: mean ratio in [0.85, 1.15], relMSE below 0.06 (the reference's own noise is
    // ~0.012 of it). With ContextFlags::NoProbeParallax (texels carried without the test) the old bounds: mean ratio
    // in [0.75, 1.15], relMSE below 0.07 (measured 89.5 %, relMSE 0.038).
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto reference = corridorReference(td);
    for (const bool parallax : {true, false}) {
        render::RasterOptions o;
        o.width = kCorridorWidth;
        o.height = kCorridorHeight;
        o.gi = true;
        o.giFlags = parallax ? 0u : uint32_t(gi::ContextFlags::NoProbeParallax);
        std::string error;
        auto gi = render::RasterRenderer::create(*td.device, scenes::corridor(), o, &error);
        INFO(error);
        REQUIRE(gi);
        frames(td, *gi, 120);
        const render::Image indirect = gi->read(render::Aov::IndirectDiffuse);
        REQUIRE(allFinite(indirect.rgb));
        if (parallax)
            checkAgainstReference("indirect-diffuse", indirect, reference.read(render::Aov::IndirectDiffuse),
                                  {.relMse = 0.06, .ssim = 0.2, .minMean = 0.85, .maxMean = 1.15});
        else
            checkAgainstReference("indirect-diffuse, NoProbeParallax", indirect, reference.read(render::Aov::IndirectDiffuse),
                                  {.relMse = 0.07, .ssim = 0.2, .minMean = 0.75, .maxMean = 1.15});
    }
    REQUIRE_NO_MESSAGES(td);
}

void glossyFloorAgainstReference(const std::string& backend) {
    // The specular path: the Cornell box with a glossy metal floor (metalness 1, roughness 0.3), whose
    // reflections of the lit walls and blocks come from GI's specular output (the pre-trace, the per-pixel
    // trace in the found brick, the SH lobe where that fails). `combined` against 512 spp of the path
    // tracer, 128², 64 frames; and the floor's own pixels (the lower third of the image), where the
    // reflections are. Measured (lavapipe and llvmpipe alike): combined relMSE 0.024, SSIM 0.80, mean 0.099
    // vs 0.119; floor relMSE 0.011, SSIM 0.79; on the floor GI adds 0.0095 where the path tracer's
    // indirect light adds 0.0157 (60 %: the same shortfall as the diffuse GI's, docs/gi.md). Without
    // specular GI the floor would show its direct light only (0.0060). Bounds: about twice the measured
    // distance from perfect.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry scene = glossyFloorCornell();
    auto gi = giRenderer(td, scene, kCornellSize);
    frames(td, *gi, 64);
    auto reference = glossyFloorReference(td);
    const render::Image combined = gi->read(render::Aov::Combined), refCombined = reference.read(render::Aov::Combined);
    REQUIRE(allFinite(combined.rgb));
    const render::ImageMetrics c = render::compareImages(combined, refCombined);
    INFO("combined relMSE " << c.relMse << " SSIM " << c.ssim << " mean " << c.meanA << " vs " << c.meanB);
    auto lowerThird = [](const render::Image& img) {
        render::Image out;
        out.width = img.width;
        out.height = img.height / 3;
        out.rgb.assign(img.rgb.end() - ptrdiff_t(3 * size_t(out.width) * out.height), img.rgb.end());
        return out;
    };
    const render::ImageMetrics f = render::compareImages(lowerThird(combined), lowerThird(refCombined));
    INFO("floor relMSE " << f.relMse << " SSIM " << f.ssim << " mean " << f.meanA << " vs " << f.meanB);
    // What GI adds on the floor (combined - direct; a metal has no diffuse term, so this is the specular
    // GI), against what the path tracer's indirect light adds there.
    const double giAdds = f.meanA - imageMean(lowerThird(gi->read(render::Aov::Direct)));
    const double referenceAdds = f.meanB - imageMean(lowerThird(reference.read(render::Aov::Direct)));
    INFO("on the floor GI adds " << giAdds << ", the path tracer's indirect light " << referenceAdds);
    CHECK(c.relMse < 0.05);
    CHECK(c.ssim > 0.65);
    CHECK(f.relMse < 0.025);
    CHECK(f.ssim > 0.6);
    CHECK(giAdds > 0.4 * referenceAdds);
    CHECK(giAdds < 1.3 * referenceAdds);
    REQUIRE_NO_MESSAGES(td);
}

void noFlickerWhenConverged(const std::string& backend) {
    // A static view after convergence: the mean absolute change between two consecutive frames is below
    // 2 % of the mean GI (temporal accumulation and the caches' slow weights keep it still). Measured:
    // 0.7 %.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto gi = giRenderer(td, scenes::cornellBox());
    frames(td, *gi, 40);
    const render::Image a = gi->read(render::Aov::IndirectDiffuse);
    frames(td, *gi, 1);
    const render::Image b = gi->read(render::Aov::IndirectDiffuse);
    double change = 0.0;
    for (size_t i = 0; i < a.rgb.size(); ++i) change += std::fabs(double(a.rgb[i]) - b.rgb[i]);
    change /= double(a.rgb.size());
    INFO("mean change " << change << " mean " << imageMean(a));
    CHECK(change < 0.02 * imageMean(a));
    REQUIRE_NO_MESSAGES(td);
}

void noLeakThroughWall(const std::string& backend) {
    // two-rooms: the camera in the closed room B looks at the wall it shares with the sunlit room A
    // (wall 0.25 m thick; the finest voxel here is ~0.14 m). The reference's light in room B is exactly
    // zero; GI's indirect light there must stay below 1 % of the indirect light in room A (seen from
    // inside A through the same GI). Measured: 2e-8 against 0.045.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    scenes::SceneGeometry rooms = scenes::twoRooms(0.25f);
    auto dark = giRenderer(td, rooms);
    frames(td, *dark, 40);
    const double leak = imageMean(dark->read(render::Aov::IndirectDiffuse));
    scenes::SceneGeometry lit = rooms;
    lit.camera.eye = glm::vec3(0.5f, 1.6f, 2.0f);
    lit.camera.at = glm::vec3(4.0f, 1.0f, 2.0f);
    auto bright = giRenderer(td, lit);
    frames(td, *bright, 40);
    const double light = imageMean(bright->read(render::Aov::IndirectDiffuse));
    INFO("room B " << leak << " room A " << light);
    CHECK(light > 0.0);
    CHECK(leak < 0.01 * light);
    REQUIRE_NO_MESSAGES(td);
}

void recoversAfterMotion(const std::string& backend) {
    // dynamic: the torus and the light move for 24 frames, then stop. GI must move towards what a renderer
    // that saw only the final state reaches in as many frames (each check against the still renderer at the
    // moving one's frame count: the multi-bounce feedback is still brightening at 128 frames, 128 against 256
    // frames differ by relMSE ~0.01, so a comparison with a still renderer further along measures convergence,
    // not light left behind): 24 frames after the stop (48 frames each) below 0.013 and below its value at the
    // stop; 104 frames after, below 0.015; 232 frames after, below 0.0075 — no light left behind by the moving
    // lamp. Measured on lavapipe / llvmpipe with the unseen hits lit where they are met (fill_probes_body.glsl):
    // 0.022–0.023 at the stop, 0.0089–0.0100 after 24 (the moving renderer 4.5 % brighter than the still one:
    // it has seen more of the room), 0.0035–0.0041 after 104, 0.0019–0.0024 after 232. Before that (the +24 and
    // +104 checks then against the still renderer at 128 frames): ~0.019 at the stop, 0.0051–0.0071 after 24,
    // 0.0039–0.0067 after 104, 0.0017–0.0026 after 232; on an H100 (1013 runs, 2026-11-24) 0.0022–0.0060 after
    // 232, and one GL run of the 1013 wrong at every check (0.15 at the stop, 0.10 at +232), which the test
    // still fails (docs/gi.md, *Known limitations*; docs/notes/gi-quality.md has the H100 history). Without
    // relighting: 0.020, 0.0062, then 0.0041 and rising.
    // The room with the torus and the light only (no crowd, no deforming mesh): the figures above are of it.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    scenes::SceneGeometry scene = scenes::dynamicRoom({false, false});
    auto moving = giRenderer(td, scene, 48);
    std::string error;
    for (uint32_t f = 1; f <= 24; ++f) {
        scene.animate(scene, f);
        REQUIRE(moving->setScene(scene, &error));
        frames(td, *moving, 1);
    }
    auto still = giRenderer(td, scene, 48);  // the final state from the start
    frames(td, *still, 48);
    const render::Image stillAt48 = still->read(render::Aov::IndirectDiffuse);  // not converged yet: see above
    frames(td, *still, 80);
    const render::Image stillAt128 = still->read(render::Aov::IndirectDiffuse);
    REQUIRE(moving->setScene(scene, &error));  // the same state again: no more motion vectors
    // Each comparison also reports both images' means (moving / still), which tell a failure in the
    // renderer that moved from one in the still renderer.
    std::ostringstream means;
    auto compare = [&](const render::Image& reference) {
        const render::ImageMetrics m = render::compareImages(moving->read(render::Aov::IndirectDiffuse), reference);
        means << " " << m.meanA << "/" << m.meanB;
        return m.relMse;
    };
    frames(td, *moving, 1);
    const double atStop = compare(stillAt48);
    frames(td, *moving, 23);
    const double after = compare(stillAt48);
    frames(td, *moving, 80);
    const double later = compare(stillAt128);
    frames(td, *moving, 128);
    frames(td, *still, 128);
    const double settled = compare(still->read(render::Aov::IndirectDiffuse));
    INFO("relMSE to the still scene's GI: " << atStop << " at the stop, " << after << " 24 frames later, " << later << " 104 frames later, "
                                              << settled << " 232 frames later; means (moving/still):" << means.str());
    CHECK(after < 0.013);
    CHECK(after < atStop);
    CHECK(later < 0.015);
    CHECK(settled < 0.0075);
    REQUIRE_NO_MESSAGES(td);
}

void badInputChangesNothing(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    std::vector<std::string> messages;
    auto gi = giRenderer(td, scenes::cornellBox(), 32);
    frames(td, *gi, 2);
    gi::GiContext* context = gi->giContext();
    REQUIRE(context);
    const render::GBufferView g = gi->gbuffer();
    rhi::TextureDesc od;
    od.format = rhi::Format::RGBA16_FLOAT;
    od.width = od.height = 32;
    od.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    od.debugName = "test diffuse";
    rhi::TextureHandle out = td.device->createTexture(od);
    od.debugName = "test specular";
    rhi::TextureHandle outSpecular = td.device->createTexture(od);
    od.width = 16;
    od.debugName = "small output";
    rhi::TextureHandle small = td.device->createTexture(od);
    od.width = 32;
    od.format = rhi::Format::RGBA8_UNORM;
    od.debugName = "rgba8 output";
    rhi::TextureHandle wrongFormat = td.device->createTexture(od);
    const gi::DispatchDesc good = giInputsOf(g, out, outSpecular);
    gi::Light light, negative;
    light.color = glm::vec3(1.0f);
    negative.color = glm::vec3(1.0f, -1.0f, 1.0f);
    struct Case {
        const char* expect;
        std::function<void(gi::DispatchDesc&)> spoil;
    };
    const Case cases[] = {
        {"input 'depth' is missing", [](gi::DispatchDesc& d) { d.gbuffer.depth = {}; }},
        {"must be the display size", [&](gi::DispatchDesc& d) { d.gbuffer.depth = small; }},
        {"output 'outputSpecular' (texture 'small output') is 16x32", [&](gi::DispatchDesc& d) { d.outputSpecular = small; }},
        {"must be a 2D RGBA16_FLOAT texture", [&](gi::DispatchDesc& d) { d.outputDiffuse = wrongFormat; }},
        {"roughnessChannel 7", [](gi::DispatchDesc& d) { d.gbuffer.roughnessChannel = 7; }},
        {"matrix 'projection' is not finite", [](gi::DispatchDesc& d) { d.camera.projection[0][0] = NAN; }},
        {"trace.startCascade 9", [](gi::DispatchDesc& d) { d.trace.startCascade = 9; }},
        {"trace.maxIterationsPerCascade 0 is outside", [](gi::DispatchDesc& d) { d.trace.maxIterationsPerCascade = 0; }},
        {"trace.coarsenAfterVoxels must be finite", [](gi::DispatchDesc& d) { d.trace.coarsenAfterVoxels = NAN; }},
        {"environmentMap is missing", [](gi::DispatchDesc& d) { d.environmentKind = gi::EnvironmentKind::Cube; }},
        {"texture 'gbuffer lit' is bound as output 'outputDiffuse' and as input 'previousLitOutput'", [&](gi::DispatchDesc& d) { d.outputDiffuse = g.lit; }},
        {"lights are given without 'diffuseAlbedo'", [&](gi::DispatchDesc& d) {
             d.lights = &light;
             d.lightCount = 1;
         }},
        {"lights[0] has a negative color", [&](gi::DispatchDesc& d) {
             d.diffuseAlbedo = g.albedo;
             d.lights = &negative;
             d.lightCount = 1;
         }},
        {"lightCount 65 is above kMaxLights", [&](gi::DispatchDesc& d) {
             d.diffuseAlbedo = g.albedo;
             d.lights = &light;
             d.lightCount = 65;
         }},
        {"input 'diffuseAlbedo' (texture 'small output') is 16x32", [&](gi::DispatchDesc& d) { d.diffuseAlbedo = small; }},
        {"'emission' is given without 'diffuseAlbedo'", [&](gi::DispatchDesc& d) { d.emission = g.emission; }},
    };
    std::vector<float> before, after;
    context->readCaches(&before, nullptr);
    for (const Case& c : cases) {
        gi::DispatchDesc d = good;
        c.spoil(d);
        CHECK_FALSE(context->dispatch(d));
        INFO("message: " << context->lastError().message);
        CHECK(context->lastError().message.find(c.expect) != std::string::npos);
    }
    context->readCaches(&after, nullptr);
    CHECK(before == after);  // a rejected dispatch records nothing
    CHECK(context->dispatch(good));  // and the context still works
    for (rhi::TextureHandle t : {out, outSpecular, small, wrongFormat}) td.device->destroy(t);
}

void fullCacheDegradesGracefully(const std::string& backend) {
    // A radiance cache of 32 brick slots for the Cornell box (which puts light in a few hundred): the
    // slots fill up, the bricks left without one stay uncached (their hits count as unknown), and GI stays
    // finite and keeps some light. A context asking for more slots than the scene has bricks is refused
    // with a message.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto r = giRenderer(td, scenes::cornellBox(), 32, true, 32);
    frames(td, *r, 16);
    CHECK(r->giContext()->radianceCacheBricksInUse() == 32);
    const render::Image indirect = r->read(render::Aov::IndirectDiffuse);
    CHECK(allFinite(indirect.rgb));
    CHECK(imageMean(indirect) > 0.0);
    auto full = giRenderer(td, scenes::cornellBox(), 32);
    frames(td, *full, 16);
    const uint32_t used = full->giContext()->radianceCacheBricksInUse();
    INFO("slots in use with the default cache: " << used);
    CHECK(used > 32);
    REQUIRE_NO_MESSAGES(td);
    gi::ContextDesc cd;
    cd.radianceCacheBricks = full->sdfScene()->brickCapacity() + 1;
    CHECK(refusal(td, *full->sdfScene(), cd).find("radianceCacheBricks") != std::string::npos);
}

void widerInjectionTiles(const std::string& backend) {
    // Injecting one pixel of each 4×4 tile a frame (the default from an internal width of 1440 on) or 8×8
    // instead of each 2×2 tile: each injection weighs more (inject_radiance.comp), so the Cornell box
    // converges to about the same light. At 64² with 4×4 tiles only 256 pixels inject a frame, so each cache
    // texel takes most of its value from its latest injection, and which racing thread wrote last (the
    // driver's thread schedule) steers the bounce feedback for many frames: over ~40 runs (lavapipe with 1–8
    // threads) the 4×4 relMSE to 2×2 tiles (mean of the last 8 of 48 frames) was 0.001–0.002
    // typically, up to 0.011 here and 0.020 once on CI, its mean 2–5 % lower and once 6.2 % higher; 8×8 —
    // 64 injected pixels a frame, far fewer than the default would ever use — relMSE 0.002–0.006, mean
    // 2.5–8.6 % lower. Bounds: relMSE < 0.04 / 0.04, means within 10 % / 14 % (a weight not scaled with the
    // tile leaves the cache far from converged after 48 frames; skipped pixels leave bricks black).
    // An injectTile that is not 0, 1, 2, 4 or 8 is refused with a message.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto reference = giRenderer(td, scenes::cornellBox(), kSize, true, 0, 2);
    const render::Image expected = averagedFrames(td, *reference, 48, 8, render::Aov::IndirectDiffuse);
    struct Bound {
        uint32_t tile;
        double relMse, meanShare;
    };
    for (const Bound b : {Bound{4, 0.04, 0.10}, Bound{8, 0.04, 0.14}}) {
        auto wide = giRenderer(td, scenes::cornellBox(), kSize, true, 0, b.tile);
        const render::ImageMetrics m =
            render::compareImages(averagedFrames(td, *wide, 48, 8, render::Aov::IndirectDiffuse), expected);
        INFO(b.tile << "x" << b.tile << " tiles: relMSE " << m.relMse << ", mean " << m.meanA << " vs " << m.meanB);
        CHECK(m.relMse < b.relMse);
        CHECK(std::fabs(m.meanA - m.meanB) < b.meanShare * m.meanB);
    }
    REQUIRE_NO_MESSAGES(td);
    gi::ContextDesc cd;
    cd.injectTile = 3;
    CHECK(refusal(td, *reference->sdfScene(), cd).find("injectTile 3") != std::string::npos);
}

void widerProbeTiles(const std::string& backend) {
    // One screen probe per 16×16 tile (the default from an internal width of 1440 on) instead of 8×8: the
    // probes carry low-frequency light, and the interpolation, the blur and the world cache fill in
    // between, so the Cornell box converges to about the same light. At 128² this is 8×8 probes against
    // 16×16 — far fewer per screen than the default would ever use (120×68 at 1920x1080 internal).
    // Measured (lavapipe / llvmpipe, 48 frames): relMSE 0.0020, SSIM 0.944, mean 5.0 % lower with 16×16
    // tiles. Bounds: relMSE < 0.006, SSIM > 0.9, mean within 10 %.
    // A probeTile that is not 0, 8 or 16 is refused with a message.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto reference = giRenderer(td, scenes::cornellBox(), kCornellSize, true, 0, 0, 8);
    const render::Image expected = averagedFrames(td, *reference, 48, 8, render::Aov::IndirectDiffuse);
    auto wide = giRenderer(td, scenes::cornellBox(), kCornellSize, true, 0, 0, 16);
    CHECK(wide->giContext()->probeTile() == 16);
    const render::ImageMetrics m =
        render::compareImages(averagedFrames(td, *wide, 48, 8, render::Aov::IndirectDiffuse), expected);
    INFO("16x16 probe tiles: relMSE " << m.relMse << ", SSIM " << m.ssim << ", mean " << m.meanA << " vs " << m.meanB);
    CHECK(m.relMse < 0.006);
    CHECK(m.ssim > 0.9);
    CHECK(std::fabs(m.meanA - m.meanB) < 0.1 * m.meanB);
    REQUIRE_NO_MESSAGES(td);
    gi::ContextDesc cd;
    cd.probeTile = 12;
    CHECK(refusal(td, *reference->sdfScene(), cd).find("probeTile 12") != std::string::npos);
    cd.displayWidth = 2880;  // 1440 internal at the default 50 %: automatic tiles are 16×16
    cd.displayHeight = 64;
    cd.probeTile = 0;
    Error error;
    auto automatic = gi::GiContext::create(*td.device, *reference->sdfScene(), cd, &error);
    INFO(error.message);
    REQUIRE(automatic);
    CHECK(automatic->probeTile() == 16);
}

// GI's diffuse output on `scene` after 40 frames in which every surface sends radiance 1 (the lit image is
// overwritten with 1 after each frame).
// GI fed a lit image of radiance 1 everywhere. Relighting is off: it would re-light what the camera does
// not see from the scene's real lights and albedo, not from the furnace's made-up radiance.
render::Image furnaceGi(TestDevice& td, const scenes::SceneGeometry& scene) {
    auto gi = giRenderer(td, scene, 32, false);
    const render::GBufferView g = gi->gbuffer();
    const std::vector<uint16_t> one(32 * 32 * 4, 0x3C00);
    for (int f = 0; f < 40; ++f) {
        gi->render();
        td.device->writeTexture(g.lit, {}, one.data());
        td.device->endFrame();
    }
    return gi->read(render::Aov::IndirectDiffuse);
}

void openFurnace(const std::string& backend) {
    // The Cornell box (open at the front) with every surface sending radiance 1: GI's diffuse output is the
    // cosine-weighted fraction of directions that hit the box. The path tracer gives the same fraction as
    // its indirect light when every albedo is 1 and the sky is 1 (all light escapes eventually, so every
    // surface's radiance is 1). Measured: GI 0.663, path tracer 0.675 (ratio 0.98). Bound: ratio in
    // [0.9, 1.1].
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const double giMean = imageMean(furnaceGi(td, scenes::cornellBox()));
    scenes::SceneGeometry white = scenes::cornellBox();
    for (auto& m : white.meshes) {
        m.albedo = glm::vec3(1.0f);
        m.emission = glm::vec3(0.0f);
    }
    white.environment.skyRadiance = glm::vec3(1.0f);
    const double reference = imageMean(pathTraced(td, white, 32, 256).read(render::Aov::IndirectDiffuse));
    INFO("GI " << giMean << " path tracer " << reference);
    CHECK(giMean > 0.9 * reference);
    CHECK(giMean < 1.1 * reference);
}

void furnace(const std::string& backend) {
    // A furnace: inside the closed room B of two-rooms, every surface sends radiance 1 (the lit image is
    // overwritten with 1 each frame), so every pixel's incoming light is 1 from all directions and the
    // diffuse output (irradiance / pi) must be 1. Measured: mean 1.015, no value off by more than 15 %.
    // Bounds: mean within 5 %, at most 2 % of values off by more than 15 %.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const render::Image indirect = furnaceGi(td, scenes::twoRooms(0.25f));
    const double m = imageMean(indirect);
    size_t off = 0;
    for (float v : indirect.rgb) off += std::fabs(v - 1.0f) > 0.15f;
    INFO("mean " << m << ", " << off << " of " << indirect.rgb.size() << " values off by > 15 %");
    CHECK(std::fabs(m - 1.0) < 0.05);
    CHECK(off < indirect.rgb.size() * 2 / 100);
}

void depthReconstruction(const std::string& backend) {
    // GI rebuilds positions from depth with the inverse view-projection: on the renderer's G-buffer (near
    // plane 1e-5 of the far plane) they must land on the rasterized positions within 0.2 % of the distance.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    auto gi = giRenderer(td, cornell, 32);
    frames(td, *gi, 1);
    const render::GBufferView g = gi->gbuffer();
    std::vector<float> depth(32 * 32);
    std::vector<glm::vec4> position(32 * 32);
    td.device->readTexture(g.depth, {}, depth.data());
    td.device->readTexture(g.position, {}, position.data());
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(g.projection) * glm::dmat4(g.view));
    double worst = 0.0;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            const size_t i = y * 32 + x;
            if (position[i].w == 0.0f) continue;
            const glm::dvec4 p = inverse * glm::dvec4((x + 0.5) / 16.0 - 1.0, (y + 0.5) / 16.0 - 1.0, depth[i], 1.0);
            const glm::dvec3 q = glm::dvec3(p) / p.w;
            const double e = glm::length(q - glm::dvec3(position[i])) / glm::length(glm::dvec3(position[i]) - glm::dvec3(g.eye));
            worst = std::max(worst, e);
        }
    INFO("worst relative error " << worst);
    CHECK(worst < 2e-3);
}

void nanDoesNotPoisonCaches(const std::string& backend) {
    // NaN in last frame's lit image (every other texel) and in the G-buffer's normals: the caches and the
    // outputs stay finite, and GI still converges to light where the inputs are good.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto gi = giRenderer(td, scenes::cornellBox(), 32);
    const render::GBufferView g = gi->gbuffer();
    std::vector<uint16_t> poisoned(32 * 32 * 4, 0x3C00);  // 1.0
    for (size_t i = 0; i < poisoned.size(); i += 8) poisoned[i] = 0x7E00;  // NaN
    for (int f = 0; f < 12; ++f) {
        gi->render();
        td.device->writeTexture(g.lit, {}, poisoned.data());  // what the next frame's GI reads
        if (f % 3 == 0) td.device->writeTexture(g.normal, {}, poisoned.data());
        td.device->endFrame();
    }
    std::vector<float> radiance, sh;
    gi->giContext()->readCaches(&radiance, &sh);
    CHECK(allFinite(radiance));
    CHECK(allFinite(sh));
    const render::Image indirect = gi->read(render::Aov::IndirectDiffuse);
    CHECK(allFinite(indirect.rgb));
    CHECK(imageMean(indirect) > 0.0);
}

// A closed room lit only by a spot light aimed at its +z end, behind the camera, which looks at the -z end
// (the lit end is entirely off screen). The camera first looks at the lit end, so the cache knows it.
struct OffscreenLightRun {
    double lit = 0.0, off = 0.0, back = 0.0;  // mean indirect light on screen: light on, switched off, on again
};
OffscreenLightRun offscreenLightRun(TestDevice& td, bool relight) {
    scenes::SceneGeometry room = scenes::dynamicRoom();
    room.meshes.resize(1);  // the bare room: no torus, no ceiling light
    room.instances.resize(1);
    room.animate = nullptr;
    scenes::PointLight spot;
    spot.position = glm::vec3(0.0f, 2.8f, 0.5f);
    spot.direction = glm::normalize(glm::vec3(0.0f, -2.8f, 2.3f));
    spot.innerConeRadians = glm::radians(20.0f);
    spot.outerConeRadians = glm::radians(30.0f);
    spot.intensity = glm::vec3(40.0f);
    room.pointLights = {spot};
    room.computeBounds();
    auto r = giRenderer(td, room, 48, relight);
    std::string error;
    scenes::Camera towardsLight{glm::vec3(0.0f, 1.6f, -1.0f), glm::vec3(0.0f, 1.0f, 3.0f), glm::vec3(0, 1, 0), 75.0f};
    scenes::Camera awayFromLight{glm::vec3(0.0f, 1.6f, 1.0f), glm::vec3(0.0f, 1.2f, -3.0f), glm::vec3(0, 1, 0), 75.0f};
    REQUIRE(r->setCamera(towardsLight, &error));
    frames(td, *r, 24);
    REQUIRE(r->setCamera(awayFromLight, &error));
    r->cameraCut();
    frames(td, *r, 32);
    OffscreenLightRun run;
    run.lit = imageMean(r->read(render::Aov::IndirectDiffuse));
    const render::Image directLit = r->read(render::Aov::Direct);
    room.pointLights[0].intensity = glm::vec3(0.0f);
    REQUIRE(r->setScene(room, &error));
    frames(td, *r, 40);
    run.off = imageMean(r->read(render::Aov::IndirectDiffuse));
    // The light never reaches the screen directly: what GI shows is all it knows from off screen.
    CHECK(imageMean(directLit) < 1e-3 * run.lit);
    room.pointLights[0].intensity = glm::vec3(40.0f);
    REQUIRE(r->setScene(room, &error));
    frames(td, *r, 40);
    run.back = imageMean(r->read(render::Aov::IndirectDiffuse));
    return run;
}

void followsOffscreenLight(const std::string& backend) {
    // A spot light behind the camera is switched off, then on again; the camera never sees the surfaces it
    // lights. Without relighting the cache keeps what it saw: 40 frames after the switch-off the indirect
    // light on screen is still above 85 % of its lit value (measured: 98 % on lavapipe, 90 % on an NVIDIA
    // H100), though the exact
    // answer is 0 — the run that shows the test tells the two apart. With relighting (the renderer passes
    // GI the albedo and the lights) it follows: below 70 % of its lit value 40 frames after the switch-off
    // (measured: 61 %) and back above 70 % 40 frames after the switch-on (measured: 83 %). What remains
    // after 40 frames is the room's multi-bounce light, which converges through the screen's feedback
    // loop at the pace of its temporal history (docs/gi.md, "Relighting").
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const OffscreenLightRun with = offscreenLightRun(td, true);
    const OffscreenLightRun without = offscreenLightRun(td, false);
    INFO("relit: lit " << with.lit << " off " << with.off << " back " << with.back << "; not relit: lit " << without.lit << " off "
                       << without.off << " back " << without.back);
    REQUIRE(with.lit > 0.0);
    REQUIRE(without.lit > 0.0);
    CHECK(without.off > 0.85 * without.lit);
    CHECK(with.off < 0.7 * with.lit);
    CHECK(with.off < 0.8 * without.off);
    CHECK(with.back > 0.7 * with.lit);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("GI follows light that changes off screen", "[gi]", followsOffscreenLight)
BACKEND_TEST("GI with a full radiance cache stays finite and lit", "[gi]", fullCacheDegradesGracefully)
BACKEND_TEST("GI on the Cornell box against the path tracer", "[gi]", cornellAgainstReference)
BACKEND_TEST("GI's single bounce on the Cornell box against the path tracer's", "[gi]", cornellSingleBounceAgainstReference)
BACKEND_TEST("GI's specular on a glossy floor against the path tracer", "[gi]", glossyFloorAgainstReference)
BACKEND_TEST("GI around a corner of single-sided walls against the path tracer", "[gi]", corridorAgainstReference)
BACKEND_TEST("GI does not flicker on a static view", "[gi]", noFlickerWhenConverged)
BACKEND_TEST("GI does not leak through a wall", "[gi]", noLeakThroughWall)
BACKEND_TEST("GI rejects bad input and records nothing", "[gi]", badInputChangesNothing)
BACKEND_TEST("GI settles after motion stops", "[gi]", recoversAfterMotion)
BACKEND_TEST("GI with wider injection tiles converges to the same light", "[gi]", widerInjectionTiles)
BACKEND_TEST("GI with wider probe tiles converges to the same light", "[gi]", widerProbeTiles)
BACKEND_TEST("GI keeps NaN out of its caches", "[gi]", nanDoesNotPoisonCaches)
BACKEND_TEST("GI in a furnace returns the furnace's radiance", "[gi][quick]", furnace)
BACKEND_TEST("GI in an open furnace sees the box as the path tracer does", "[gi]", openFurnace)
BACKEND_TEST("GI's positions from depth match the rasterized ones", "[gi]", depthReconstruction)

#if defined(BRICKLIGHT_HAS_VULKAN) && defined(BRICKLIGHT_HAS_GL)
TEST_CASE("GI on Vulkan and GL agree", "[gi][cross]") {
    // The same 24 frames on both backends, with relighting off and on. The passes race where threads blend
    // into the same cache texel or brick (last writer wins), so the two differ by noise, not by bias:
    // relMSE below 0.01 and means within 5 %. Relighting touches only bricks out of view (outside the
    // frustum or behind the depth buffer), so it adds no race-dependent change to what the camera sees.
    // (When it re-lit bricks "not injected lately", coarse bricks in view were re-lit by chance and the
    // means drifted up to 12.7 % apart; docs/gi.md, "Relighting".)
    for (bool relight : {false, true}) {
        render::Image images[2];
        int k = 0;
        for (const char* backend : {"vulkan", "gl"}) {
            TestDevice td = makeDevice(backend);
            REQUIRE(td.device);
            auto gi = giRenderer(td, scenes::cornellBox(), kSize, relight);
            frames(td, *gi, 24);
            images[k++] = gi->read(render::Aov::IndirectDiffuse);
        }
        const render::ImageMetrics m = render::compareImages(images[1], images[0]);
        INFO("relighting " << (relight ? "on" : "off") << ": relMSE " << m.relMse << " mean " << m.meanA << " vs " << m.meanB);
        CHECK(m.relMse < 0.01);
        CHECK(std::fabs(m.meanA - m.meanB) < 0.05 * m.meanB);
    }
}
#endif
