// Base-colour textures: a textured quad shows its texels in the path tracer's and the fast path's albedo
// (the same values), and a texture that cannot be loaded is a clear error. Alpha-tested materials: the
// G-buffer draw, the shadow maps and the rays of the path tracer and of the direct lighting leave out what is
// below the cut-off.
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>

#include "backend_test.h"
#include "path_tracer.h"
#include "raster_renderer.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

// A 64 x 64 texture of four solid quadrants: red, green (top row), blue, white.
std::string writeChecker(const std::string& backend) {
    const std::string path = "texture_tests_checker_" + backend + ".png";  // tests of both backends run in parallel
    std::vector<uint8_t> texels(64 * 64 * 3);
    const uint8_t colours[4][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}};
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) texels[size_t(y * 64 + x) * 3 + size_t(c)] = colours[(y / 32) * 2 + x / 32][c];
    auto out = OIIO::ImageOutput::create(path);
    REQUIRE(out);
    REQUIRE(out->open(path, OIIO::ImageSpec(64, 64, 3, OIIO::TypeDesc::UINT8)));
    REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, texels.data()));
    out->close();
    return path;
}

scenes::SceneGeometry texturedQuad(const std::string& texture) {
    scenes::SceneGeometry s;
    scenes::TriangleMesh quad;
    quad.name = "textured quad";
    quad.positions = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    quad.uvs = {0, 1, 1, 1, 1, 0, 0, 0};  // v down the image: the texture's top row at y = +1
    quad.indices = {0, 1, 2, 0, 2, 3};
    quad.albedo = glm::vec3(1.0f);
    quad.baseColorTexture = texture;
    s.meshes.push_back(quad);
    s.instances.push_back({0, glm::mat4(1.0f)});
    s.environment.skyRadiance = glm::vec3(1.0f);
    s.camera = {glm::vec3(0, 0, 3), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0), 30.0f};
    s.computeBounds();
    return s;
}

void texturedAlbedo(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry s = texturedQuad(writeChecker(backend));
    Pair both = makePair(td, s, 32, 1, 1, false);
    const render::Image traced = both.tracer->read(render::Aov::Albedo), rastered = both.raster->read(render::Aov::Albedo);
    // The quad fills the middle of the view; the quadrants' centres show the texels (sRGB 255 -> 1, 0 -> 0).
    struct Probe { uint32_t x, y; glm::vec3 colour; };
    for (const Probe& p : {Probe{12, 12, {1, 0, 0}}, Probe{19, 12, {0, 1, 0}}, Probe{12, 19, {0, 0, 1}}, Probe{19, 19, {1, 1, 1}}}) {
        const glm::vec3 t = traced.at(p.x, p.y);
        INFO("pixel " << p.x << "," << p.y << ": traced " << t.x << "," << t.y << "," << t.z);
        CHECK(glm::length(t - p.colour) < 0.02f);
    }
    double worst = 0.0;
    for (size_t i = 0; i < traced.rgb.size(); ++i) worst = std::max(worst, double(std::fabs(traced.rgb[i] - rastered.rgb[i])));
    INFO("largest albedo difference between the paths " << worst);
    CHECK(worst < 5e-3);  // the same texel lookups; 16-bit float G-buffer
    REQUIRE_NO_MESSAGES(td);
}

void missingTexture(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    std::string error;
    render::PathTracerOptions po;
    po.width = po.height = 8;
    CHECK(!render::PathTracer::create(*td.device, texturedQuad("no/such/texture.png"), po, &error));
    INFO(error);
    CHECK(error.find("'textured quad'") != std::string::npos);
    CHECK(error.find("no/such/texture.png") != std::string::npos);
    CHECK(error.find("cannot be loaded") != std::string::npos);
    REQUIRE_NO_MESSAGES(td);
}

// A 64 x 64 image of `channels` channels, the left half `left`, the right half `right`: in the alpha of an RGBA
// image (white), in every channel of an RGB one.
std::string writeHalves(const std::string& name, int channels, uint8_t left, uint8_t right) {
    std::vector<uint8_t> texels(64 * 64 * size_t(channels));
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < channels; ++c)
                texels[size_t(y * 64 + x) * size_t(channels) + size_t(c)] = channels == 4 && c < 3 ? 255 : x < 32 ? left : right;
    auto out = OIIO::ImageOutput::create(name);
    REQUIRE(out);
    OIIO::ImageSpec spec(64, 64, channels, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // the colour as given where alpha is 0 (not premultiplied to black)
    REQUIRE(out->open(name, spec));
    REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, texels.data()));
    out->close();
    return name;
}

// texturedQuad (albedo green) in front of a larger red wall.
scenes::SceneGeometry quadBeforeWall(const std::string& texture) {
    scenes::SceneGeometry s = texturedQuad(texture);
    s.meshes[0].albedo = glm::vec3(0, 1, 0);
    scenes::TriangleMesh wall;
    wall.name = "wall";
    wall.positions = {-3, -3, -1, 3, -3, -1, 3, 3, -1, -3, 3, -1};
    wall.indices = {0, 1, 2, 0, 2, 3};
    wall.albedo = glm::vec3(1, 0, 0);
    s.meshes.push_back(wall);
    s.instances.push_back({1, glm::mat4(1.0f)});
    s.computeBounds();
    return s;
}

void alphaTestedGbuffer(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    // White RGBA, transparent on the left half (alpha 0), opaque on the right (255); and a grey coverage map
    // (RGB, no alpha) black on the left, white on the right.
    const std::string rgba = writeHalves("alpha_tests_rgba_" + backend + ".png", 4, 0, 255);
    const std::string white = writeHalves("alpha_tests_white_" + backend + ".png", 3, 255, 255);
    const std::string coverageMap = writeHalves("alpha_tests_coverage_" + backend + ".png", 3, 0, 255);
    const glm::vec3 quad(0, 1, 0), wall(1, 0, 0);
    const struct {
        const char* name;
        std::string texture, alphaTexture;
        float cutoff, baseAlpha;
        glm::vec3 left, right;  // what the quad's halves show
    } cases[] = {
        {"the base colour texture's alpha", rgba, "", 0.5f, 1.0f, wall, quad},
        {"cut-off 0: opaque, alpha ignored", rgba, "", 0.0f, 1.0f, quad, quad},
        {"an opacity map without alpha (its first channel)", white, coverageMap, 0.5f, 1.0f, wall, quad},
        {"base alpha 0.25 below the cut-off 0.5 everywhere", rgba, "", 0.5f, 0.25f, wall, wall},
        {"base alpha 0.75 with a cut-off of 0.7", rgba, "", 0.7f, 0.75f, wall, quad},
    };
    for (const auto& c : cases) {
        INFO(c.name);
        scenes::SceneGeometry s = quadBeforeWall(c.texture);
        s.meshes[0].alphaCutoff = c.cutoff;
        s.meshes[0].baseAlpha = c.baseAlpha;
        s.meshes[0].alphaTexture = c.alphaTexture;
        render::RasterOptions ro;
        ro.width = ro.height = 32;
        std::string error;
        auto raster = render::RasterRenderer::create(*td.device, s, ro, &error);
        INFO(error);
        REQUIRE(raster);
        raster->render();
        const render::Image albedo = raster->read(render::Aov::Albedo);
        // The quad fills the view (30 degrees at distance 3); its texture's halves meet at column 16.
        for (uint32_t y : {4u, 16u, 27u})
            for (uint32_t x : {4u, 12u, 19u, 27u}) {
                const glm::vec3 seen = albedo.at(x, y), expected = x < 16 ? c.left : c.right;
                INFO("pixel " << x << "," << y << ": " << seen.x << "," << seen.y << "," << seen.z);
                CHECK(glm::length(seen - expected) < 0.02f);
            }
    }
    // Values outside [0, 1] are refused by the scene.
    for (float bad : {std::nanf(""), -0.25f, 1.5f}) {
        scenes::SceneGeometry s = quadBeforeWall(rgba);
        s.meshes[0].alphaCutoff = bad;
        std::string error;
        render::RasterOptions ro;
        ro.width = ro.height = 8;
        CHECK(!render::RasterRenderer::create(*td.device, s, ro, &error));
        INFO(error);
        CHECK(error.find("mesh 'textured quad': alphaCutoff (0 opaque) and baseAlpha must be in [0, 1]") != std::string::npos);
    }
    REQUIRE_NO_MESSAGES(td);
}

// The sun's shadow maps leave the cut-out texels out: a sheet at y = 2, transparent over x < 0, above a floor that
// a camera between them sees (the sheet behind it). The floor is lit under the holes, shadowed elsewhere.
void alphaTestedShadowMaps(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const std::string rgba = writeHalves("alpha_shadow_rgba_" + backend + ".png", 4, 0, 255);
    for (float cutoff : {0.5f, 0.0f}) {
        INFO("cut-off " << cutoff);
        scenes::SceneGeometry s;
        scenes::TriangleMesh floor;
        floor.name = "floor";
        floor.positions = {-3, 0, 3, 3, 0, 3, 3, 0, -3, -3, 0, -3};
        floor.indices = {0, 1, 2, 0, 2, 3};
        scenes::TriangleMesh sheet;
        sheet.name = "sheet";
        sheet.positions = {-1, 2, 1, 1, 2, 1, 1, 2, -1, -1, 2, -1};
        sheet.uvs = {0, 1, 1, 1, 1, 0, 0, 0};  // u = (x + 1) / 2
        sheet.indices = {0, 1, 2, 0, 2, 3};
        sheet.baseColorTexture = rgba;
        sheet.alphaCutoff = cutoff;
        s.meshes = {floor, sheet};
        s.instances = {{0, glm::mat4(1.0f)}, {1, glm::mat4(1.0f)}};
        s.environment.sunDirection = glm::normalize(glm::vec3(0.0f, 1.0f, 0.1f));
        s.environment.sunIrradiance = glm::vec3(1.0f);
        // Looking straight down from y = 0.5 (image x = world x): the floor within 0.3 of the origin.
        s.camera = {glm::vec3(0, 0.5f, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1), 60.0f};
        s.computeBounds();
        render::RasterOptions ro;
        ro.width = ro.height = 32;
        ro.shadows = render::ShadowMode::ShadowMap;
        std::string error;
        auto raster = render::RasterRenderer::create(*td.device, s, ro, &error);
        INFO(error);
        REQUIRE(raster);
        raster->render();
        const render::Image visibility = raster->readSunVisibility();
        REQUIRE(visibility.width == 32);
        for (uint32_t y : {4u, 16u, 27u})
            for (uint32_t x : {4u, 10u, 22u, 27u}) {
                const float seen = visibility.at(x, y).x, expected = x < 16 && cutoff > 0.0f ? 1.0f : 0.0f;
                INFO("pixel " << x << "," << y << ": visibility " << seen);
                CHECK(std::fabs(seen - expected) < 0.05f);
            }
    }
    REQUIRE_NO_MESSAGES(td);
}

// The path tracer's camera rays pass the cut-out texels (traceRay's any-hit test): the half-transparent green
// sheet of quadBeforeWall shows the red wall behind its transparent left half, itself on the right; with
// cut-off 0 the sheet is whole.
void alphaTestedCameraRays(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const std::string rgba = writeHalves("alpha_camera_rgba_" + backend + ".png", 4, 0, 255);
    const glm::vec3 wall(1, 0, 0), sheet(0, 1, 0);
    for (float cutoff : {0.5f, 0.0f}) {
        INFO("cut-off " << cutoff);
        scenes::SceneGeometry s = quadBeforeWall(rgba);
        s.meshes[0].alphaCutoff = cutoff;
        auto pt = traced(td, s, 32, 1, false);
        const render::Image albedo = pt->read(render::Aov::Albedo);
        // The sheet covers pixels 8..23 each way (texturedAlbedo's probes); x < 16 is its transparent half.
        for (uint32_t y : {10u, 16u, 21u})
            for (uint32_t x : {10u, 13u, 18u, 21u}) {
                const glm::vec3 seen = albedo.at(x, y), expected = x < 16 && cutoff > 0.0f ? wall : sheet;
                INFO("pixel " << x << "," << y << ": albedo " << seen.x << "," << seen.y << "," << seen.z);
                CHECK(glm::length(seen - expected) < 0.02f);
            }
    }
    REQUIRE_NO_MESSAGES(td);
}

// Shadow rays pass the cut-out texels too, in the path tracer and in the fast path's ray-traced direct
// lighting (direct_light.comp): a white floor under the sheet of alphaTestedShadowMaps, lit by a sun
// straight above (no sky), gets cos / pi under the transparent half (x < 0), nothing under the opaque one;
// with cut-off 0 nothing anywhere.
void alphaTestedShadowRays(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const std::string rgba = writeHalves("alpha_rays_rgba_" + backend + ".png", 4, 0, 255);
    for (float cutoff : {0.5f, 0.0f}) {
        INFO("cut-off " << cutoff);
        scenes::SceneGeometry s;
        scenes::TriangleMesh floor = groundPlane(3.0f, glm::vec3(1.0f));
        floor.name = "floor";
        scenes::TriangleMesh sheet;
        sheet.name = "sheet";
        sheet.positions = {-1, 2, 1, 1, 2, 1, 1, 2, -1, -1, 2, -1};
        sheet.uvs = {0, 1, 1, 1, 1, 0, 0, 0};  // u = (x + 1) / 2
        sheet.indices = {0, 1, 2, 0, 2, 3};
        sheet.baseColorTexture = rgba;
        sheet.alphaCutoff = cutoff;
        s.meshes = {floor, sheet};
        s.instances = {{0, glm::mat4(1.0f)}, {1, glm::mat4(1.0f)}};
        s.environment.sunDirection = glm::normalize(glm::vec3(0.0f, 1.0f, 0.1f));
        s.environment.sunIrradiance = glm::vec3(1.0f);
        s.environment.skyRadiance = glm::vec3(0.0f);
        // Looking straight down from y = 0.5 (image x = world x): the floor within 0.3 of the origin.
        s.camera = {glm::vec3(0, 0.5f, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1), 60.0f};
        s.computeBounds();
        const float lit = glm::normalize(s.environment.sunDirection).y / float(M_PI);
        Pair both = makePair(td, s, 32, 1, 1, false);
        const render::Image traced = both.tracer->read(render::Aov::Direct), rastered = both.raster->read(render::Aov::Direct);
        for (uint32_t y : {4u, 16u, 27u})
            for (uint32_t x : {4u, 10u, 22u, 27u}) {
                const float expected = x < 16 && cutoff > 0.0f ? lit : 0.0f;
                INFO("pixel " << x << "," << y << ": path tracer " << traced.at(x, y).x << ", fast path " << rastered.at(x, y).x
                              << ", expected " << expected);
                CHECK(std::fabs(traced.at(x, y).x - expected) < 0.01f);
                CHECK(std::fabs(rastered.at(x, y).x - expected) < 0.01f);
            }
    }
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("textures: alpha-tested materials leave holes for the path tracer's camera rays", "[render]", alphaTestedCameraRays)
BACKEND_TEST("textures: alpha-tested materials leave holes for shadow rays", "[render]", alphaTestedShadowRays)
BACKEND_TEST("textures: alpha-tested materials leave holes in the sun's shadow maps", "[render][shadows]", alphaTestedShadowMaps)
BACKEND_TEST("textures: alpha-tested materials leave holes in the G-buffer", "[render]", alphaTestedGbuffer)
BACKEND_TEST("textures: base colour in both paths", "[render]", texturedAlbedo)
BACKEND_TEST("textures: a texture that cannot be loaded is a clear error", "[render]", missingTexture)
