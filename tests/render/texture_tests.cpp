// Base-colour textures: a textured quad shows its texels in the path tracer's and the fast path's albedo
// (the same values), and a texture that cannot be loaded is a clear error.
#include <OpenImageIO/imageio.h>

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

}  // namespace

BACKEND_TEST("textures: base colour in both paths", "[render]", texturedAlbedo)
BACKEND_TEST("textures: a texture that cannot be loaded is a clear error", "[render]", missingTexture)
