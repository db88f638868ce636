// Glass (TriangleMesh::transmission, ior): the path tracer's dielectric transmission conserves energy in a white
// furnace, smooth and rough; the fast path's glass pass (cone-traced refraction and reflection, --gi vxgi) against
// the path tracer on cornell-glass, closer to it than the sphere drawn opaque, showing the walls through the
// sphere; Vulkan against GL; bad materials refused. Bounds are stated where they are asserted; the figures are
// in docs/render.md and docs/vct.md.
#include <cmath>

#include "backend_test.h"
#include "image_metrics.h"
#include "path_tracer.h"
#include "raster_renderer.h"
#include "shared_references.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

// A glass sphere (1280 triangles with a sphere's vertex normals, as cornell-glass's) under a uniform sky of 1.
scenes::SceneGeometry glassUnderSky(float roughness) {
    scenes::TriangleMesh m = scenes::icosphere(3);
    m.name = "furnace glass";
    m.normals = m.positions;
    m.transmission = 1.0f;
    m.ior = 1.5f;
    m.roughness = roughness;
    return furnace(m);
}

void whiteFurnace(const std::string& backend) {
    // Glass neither absorbs nor emits: under a uniform sky of radiance 1 every pixel, through the sphere or past
    // it, sees 1 — less only what single scattering loses on rough glass. Smooth glass: every path carries exactly
    // 1 (Fresnel-chosen lobes, weight 1) but for Russian roulette's noise and the rare sample that shading normals
    // send to the wrong side of a facet. Rough glass: Walter's weight |v·m| G1 G1 / (|v·n| |m·n|), which never
    // creates energy and loses what the masking terms remove, most at grazing angles (as GGX metal does: 0.46 at
    // roughness 1, brdf_tests.cpp). 64², 256 spp; means over rings of the image (centre to silhouette) and over
    // the sphere's pixels. Measured (lavapipe): smooth every ring 0.996–1.000, mean 0.998, worst pixel 0.12 off;
    // roughness 0.1 mean 0.99; 0.3 centre 0.987 (one interface in and one out at normal incidence keep 0.999 ×
    // 0.991 by a CPU integration of the same model), mean 0.945; 0.6 mean 0.67. Bounds: no ring above 1.01;
    // smooth rings at least 0.99 and every pixel within 0.25; the centre within 2 % of 1 up to roughness 0.3.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const uint32_t size = 64;
    for (float roughness : {0.0f, 0.1f, 0.3f, 0.6f}) {
        auto pt = traced(td, glassUnderSky(roughness), size, 256);
        const render::Image c = pt->read(render::Aov::Combined), depth = pt->read(render::Aov::Depth);
        REQUIRE(allFinite(c.rgb));
        double rings[8] = {}, worst = 0.0, sum = 0.0;
        size_t ringPixels[8] = {}, n = 0;
        for (uint32_t y = 0; y < size; ++y)
            for (uint32_t x = 0; x < size; ++x) {
                const size_t p = size_t(y) * size + x;
                const double r = std::hypot(x + 0.5 - size / 2.0, y + 0.5 - size / 2.0) / (size / 2.0);
                const size_t ring = std::min<size_t>(7, size_t(r * 8.0));  // the last holds the silhouette and the corners
                rings[ring] += c.rgb[3 * p + 1];
                ++ringPixels[ring];
                for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, double(std::fabs(c.rgb[3 * p + size_t(ch)] - 1.0f)));
                if (depth.rgb[3 * p] > 0.0f) sum += c.rgb[3 * p + 1], ++n;
            }
        REQUIRE(n > 2000);  // the sphere covers most of the image
        std::string ringText;
        double lowest = 2.0, highest = 0.0;
        for (size_t i = 0; i < 8; ++i) {
            rings[i] /= double(ringPixels[i]);
            lowest = std::min(lowest, rings[i]);
            highest = std::max(highest, rings[i]);
            ringText += " " + std::to_string(rings[i]).substr(0, 6);
        }
        WARN(backend << ": glass furnace, roughness " << roughness << ": rings" << ringText << "; mean over the sphere " << sum / double(n)
                     << ", worst pixel off by " << worst);
        CHECK(highest <= 1.01);
        if (roughness == 0.0f) {
            CHECK(lowest >= 0.99);
            CHECK(worst < 0.25);
        }
        if (roughness <= 0.3f) CHECK(rings[0] >= 0.98);
        CHECK(sum / double(n) >= (roughness <= 0.1f ? 0.98 : roughness <= 0.3f ? 0.92 : 0.6));
    }
    REQUIRE_NO_MESSAGES(td);
}

constexpr uint32_t kCornellSize = 128;

render::RasterOptions vxgiOptions(uint32_t size) {
    render::RasterOptions o;
    o.width = o.height = size;
    o.gi = true;
    o.giTechnique = render::GiTechnique::Vct;
    return o;
}

render::Image fastPath(TestDevice& td, const scenes::SceneGeometry& scene, const render::RasterOptions& o, uint32_t frameCount) {
    std::string error;
    auto r = render::RasterRenderer::create(*td.device, scene, o, &error);
    INFO(error);
    REQUIRE(r);
    frames(td, *r, frameCount);
    return r->read(render::Aov::Combined);
}

// The pixels whose centre sees the glass first: the path tracer's primary-hit albedo is 0 on clear glass (and
// nowhere else in cornell-glass), with camera rays through pixel centres as the rasterizer samples.
std::vector<uint8_t> glassPixels(TestDevice& td, const scenes::SceneGeometry& scene, uint32_t size) {
    auto centres = traced(td, scene, size, 1, false);
    const render::Image albedo = centres->read(render::Aov::Albedo), depth = centres->read(render::Aov::Depth);
    std::vector<uint8_t> mask(size_t(size) * size, 0);
    for (size_t p = 0; p < mask.size(); ++p)
        mask[p] = depth.rgb[3 * p] > 0.0f && albedo.rgb[3 * p] + albedo.rgb[3 * p + 1] + albedo.rgb[3 * p + 2] == 0.0f;
    return mask;
}

void cornellGlassAgainstReference(const std::string& backend) {
    // cornell-glass, 128²: 16 frames of the fast path with --gi vxgi against 512 spp of the path tracer, over the
    // whole image and over the glass pixels; the same with the sphere drawn opaque (transmission 0: its albedo 0.9
    // and specular layer) must be farther from the reference there. Measured (lavapipe): whole relMSE 0.027, SSIM
    // 0.74, mean 0.107 vs 0.129; glass pixels (1090) relMSE 0.032, mean 0.079 vs 0.097 (81 %: what the cones gather
    // is short of the reference as on the plain Cornell box, docs/vct.md's Quality); drawn opaque relMSE 0.22, mean
    // 0.038 (the defect this test guards, glass drawn as an opaque ball, fails the last bound). After 32 frames
    // (both backends): 0.025, 0.75, 0.107; 0.035, 0.076; opaque 0.23. Bounds: about twice the distance.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry scene = scenes::cornellGlass();
    scenes::SceneGeometry opaqueScene = scene;
    for (scenes::TriangleMesh& m : opaqueScene.meshes) m.transmission = 0.0f;
    const std::vector<uint8_t> mask = glassPixels(td, scene, kCornellSize);
    size_t glassCount = 0;
    for (uint8_t m : mask) glassCount += m;
    REQUIRE(glassCount > 500);
    const render::Image glass = fastPath(td, scene, vxgiOptions(kCornellSize), 16);
    const render::Image opaque = fastPath(td, opaqueScene, vxgiOptions(kCornellSize), 16);
    REQUIRE(allFinite(glass.rgb));
    const render::Image reference = cornellGlassReference(td).read(render::Aov::Combined);  // kCornellSize², 512 spp
    const render::ImageMetrics whole = render::compareImages(glass, reference);
    const render::ImageMetrics inGlass = render::compareImages(glass, reference, &mask);
    const render::ImageMetrics asOpaque = render::compareImages(opaque, reference, &mask);
    WARN(backend << ": cornell-glass " << kCornellSize << "², " << glassCount << " glass pixels: whole relMSE " << whole.relMse << " SSIM "
                 << whole.ssim << " mean " << whole.meanA << " vs " << whole.meanB << "; glass pixels relMSE " << inGlass.relMse << " mean "
                 << inGlass.meanA << " vs " << inGlass.meanB << "; drawn opaque relMSE " << asOpaque.relMse << " mean " << asOpaque.meanA);
    CHECK(whole.relMse < 0.05);
    CHECK(whole.ssim > 0.6);
    CHECK(whole.meanA > 0.7 * whole.meanB);
    CHECK(whole.meanA < 1.2 * whole.meanB);
    CHECK(inGlass.relMse < 0.08);
    CHECK(inGlass.meanA > 0.55 * inGlass.meanB);
    CHECK(inGlass.meanA < 1.2 * inGlass.meanB);
    CHECK(inGlass.relMse < 0.5 * asOpaque.relMse);
    REQUIRE_NO_MESSAGES(td);
}

// A glass ball in front of a wall, red on the left and green on the right, under a sky of 1: a ball lens of ior
// 1.5 focuses 1.5 radii from its centre, so the wall, 3 radii behind, is seen through it upside down and
// mirrored — green on its left, red on its right.
scenes::SceneGeometry ballLens() {
    scenes::SceneGeometry s;
    for (int side = 0; side < 2; ++side) {
        scenes::TriangleMesh wall;
        wall.name = side ? "green half" : "red half";
        const float x0 = side ? 0.0f : -4.0f, x1 = side ? 4.0f : 0.0f;
        wall.positions = {x0, -3, -3, x1, -3, -3, x1, 3, -3, x0, 3, -3};  // counter-clockwise seen from +z
        wall.indices = {0, 1, 2, 0, 2, 3};
        wall.albedo = side ? glm::vec3(0.05f, 0.8f, 0.05f) : glm::vec3(0.8f, 0.05f, 0.05f);
        s.meshes.push_back(wall);
    }
    scenes::TriangleMesh ball = scenes::icosphere(3);
    ball.name = "ball";
    ball.normals = ball.positions;
    ball.transmission = 1.0f;
    ball.roughness = 0.05f;
    ball.albedo = glm::vec3(0.9f);
    s.meshes.push_back(ball);
    for (uint32_t i = 0; i < 3; ++i) s.instances.push_back({i, glm::mat4(1.0f)});
    s.environment.skyRadiance = glm::vec3(1.0f);
    s.camera = {glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0), 30.0f};
    s.computeBounds();
    return s;
}

// Green's share of red + green over the masked pixels left (or right) of the image's centre.
double greenShare(const render::Image& img, const std::vector<uint8_t>& mask, bool left) {
    double r = 0.0, g = 0.0;
    for (size_t p = 0; p < mask.size(); ++p)
        if (mask[p] && ((p % img.width) < img.width / 2) == left) r += img.rgb[3 * p], g += img.rgb[3 * p + 1];
    return g / std::max(r + g, 1e-12);
}

void seesWhatIsBehind(const std::string& backend) {
    // 64², 8 frames against 64 spp. Measured (lavapipe), green's share of red + green on the ball's left / right
    // half: path tracer 0.79 / 0.21, fast path 0.83 / 0.16, the ball drawn opaque 0.50 / 0.50. Bounds: the walls' colours cross over through the
    // glass (left at least 0.7, right at most 0.3) in both paths, and not when it is opaque.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const uint32_t size = 64;
    const scenes::SceneGeometry scene = ballLens();
    scenes::SceneGeometry opaqueScene = scene;
    opaqueScene.meshes[2].transmission = 0.0f;
    const std::vector<uint8_t> mask = glassPixels(td, scene, size);
    const render::Image glass = fastPath(td, scene, vxgiOptions(size), 8);
    const render::Image opaque = fastPath(td, opaqueScene, vxgiOptions(size), 8);
    const render::Image reference = pathTraced(td, scene, size, 64).read(render::Aov::Combined);
    const double shares[3][2] = {{greenShare(reference, mask, true), greenShare(reference, mask, false)},
                                 {greenShare(glass, mask, true), greenShare(glass, mask, false)},
                                 {greenShare(opaque, mask, true), greenShare(opaque, mask, false)}};
    WARN(backend << ": ball lens, green / (red + green) on the ball's left / right: path tracer " << shares[0][0] << " / " << shares[0][1]
                 << ", fast path " << shares[1][0] << " / " << shares[1][1] << ", drawn opaque " << shares[2][0] << " / " << shares[2][1]);
    for (int i = 0; i < 2; ++i) {
        CHECK(shares[i][0] > 0.7);
        CHECK(shares[i][1] < 0.3);
    }
    CHECK(shares[2][0] < 0.6);
    CHECK(shares[2][1] > 0.4);
    REQUIRE_NO_MESSAGES(td);
}

void opaqueWithoutClipmap(const std::string& backend) {
    // Without a clip-map there is nothing to trace through: the glass is drawn as its opaque material into the
    // G-buffer (the albedo AOV shows its albedo 0.9 on the glass pixels). With --gi vxgi the G-buffer holds what
    // lies behind the glass there (the white blocks and walls: at most 0.725) and the combined image shows the
    // glass, with light on every glass pixel.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const uint32_t size = 64;
    const scenes::SceneGeometry scene = scenes::cornellGlass();
    const std::vector<uint8_t> mask = glassPixels(td, scene, size);
    render::RasterOptions none;
    none.width = none.height = size;
    std::string error;
    for (int vxgi = 0; vxgi < 2; ++vxgi) {
        auto r = render::RasterRenderer::create(*td.device, scene, vxgi ? vxgiOptions(size) : none, &error);
        INFO(error);
        REQUIRE(r);
        frames(td, *r, 2);
        const render::Image albedo = r->read(render::Aov::Albedo), combined = r->read(render::Aov::Combined);
        size_t glassPixels = 0, asGlassAlbedo = 0, lit = 0;
        for (size_t p = 0; p < mask.size(); ++p)
            if (mask[p]) {
                ++glassPixels;
                asGlassAlbedo += std::fabs(albedo.rgb[3 * p] - 0.9f) < 1e-3f;
                lit += combined.rgb[3 * p] + combined.rgb[3 * p + 1] + combined.rgb[3 * p + 2] > 0.0f;
            }
        INFO((vxgi ? "vxgi" : "no GI") << ": " << asGlassAlbedo << " of " << glassPixels << " glass pixels have the glass's albedo");
        CHECK(asGlassAlbedo == (vxgi ? 0 : glassPixels));
        if (vxgi) CHECK(lit == glassPixels);  // (drawn opaque without GI, its side away from the light is black)
    }
    REQUIRE_NO_MESSAGES(td);
}

void refusesBadGlass(const std::string& backend) {
    // A bad glass material is refused before anything is rendered, by both paths, with the mesh and the field named.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    struct Case {
        float transmission, ior;
        const char* field;
    };
    for (const Case& c : {Case{1.0f, 1.0f, "ior"}, Case{1.0f, 0.5f, "ior"}, Case{1.0f, NAN, "ior"}, Case{0.0f, INFINITY, "ior"},
                          Case{1.0f, 3.5f, "ior"}, Case{-0.1f, 1.5f, "transmission"}, Case{1.5f, 1.5f, "transmission"},
                          Case{NAN, 1.5f, "transmission"}}) {
        scenes::SceneGeometry s = scenes::cornellGlass();
        for (scenes::TriangleMesh& m : s.meshes)
            if (m.name == "glass sphere") m.transmission = c.transmission, m.ior = c.ior;
        std::string error;
        render::PathTracerOptions po;
        po.width = po.height = 16;
        CHECK_FALSE(render::PathTracer::create(*td.device, s, po, &error));
        INFO(error);
        CHECK(error.find("'glass sphere'") != std::string::npos);
        CHECK(error.find(c.field) != std::string::npos);
        render::RasterOptions ro;
        ro.width = ro.height = 16;
        ro.gi = true;
        ro.giTechnique = render::GiTechnique::Vct;
        error.clear();
        CHECK_FALSE(render::RasterRenderer::create(*td.device, s, ro, &error));
        CHECK(error.find("'glass sphere'") != std::string::npos);
        CHECK(error.find(c.field) != std::string::npos);
    }
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("glass: the path tracer's white furnace, smooth and rough", "[glass]", whiteFurnace)
BACKEND_TEST("glass: bad transmission or ior is refused", "[glass]", refusesBadGlass)
BACKEND_TEST("glass: cornell-glass through voxel cone tracing against the path tracer", "[glass]", cornellGlassAgainstReference)
BACKEND_TEST("glass: a ball lens shows the wall behind it upside down", "[glass]", seesWhatIsBehind)
BACKEND_TEST("glass: without a clip-map it is drawn opaque", "[glass]", opaqueWithoutClipmap)

#if defined(BRICKLIGHT_HAS_VULKAN) && defined(BRICKLIGHT_HAS_GL)
TEST_CASE("glass: Vulkan and GL agree", "[glass][cross]") {
    // cornell-glass, 64²: the fast path's glass pass (8 frames of --gi vxgi) and the path tracer (64 spp, the same
    // seed) on both backends; they differ only where float rounding differs (a path sent another way at an
    // interface, a cone sample). Measured: see the WARN line. Bounds: relMSE below 1e-3, glass pixels included.
    const scenes::SceneGeometry scene = scenes::cornellGlass();
    render::Image fast[2], traced[2];
    std::vector<uint8_t> mask;
    const char* backends[2] = {"vulkan", "gl"};
    for (int b = 0; b < 2; ++b) {
        TestDevice td = makeDevice(backends[b]);
        REQUIRE(td.device);
        if (b == 0) mask = glassPixels(td, scene, 64);
        fast[b] = fastPath(td, scene, vxgiOptions(64), 8);
        traced[b] = testing::pathTraced(td, scene, 64, 64).read(render::Aov::Combined);
        REQUIRE_NO_MESSAGES(td);
    }
    const render::ImageMetrics f = render::compareImages(fast[0], fast[1]), g = render::compareImages(fast[0], fast[1], &mask);
    const render::ImageMetrics t = render::compareImages(traced[0], traced[1]);
    WARN("cornell-glass 64², Vulkan vs GL: fast path relMSE " << f.relMse << " (glass pixels " << g.relMse << "), path tracer relMSE " << t.relMse);
    CHECK(f.relMse < 1e-3);
    CHECK(g.relMse < 1e-3);
    CHECK(t.relMse < 1e-3);
}
#endif
