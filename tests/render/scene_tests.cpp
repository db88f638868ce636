// The built-in scenes: the light-leak scene has exactly no light in its closed room (so any light a
// technique puts there is a leak), the dynamic scene moves and its motion vectors show it, scene names
// with bad parameters are refused.
#include <cmath>

#include "backend_test.h"
#include "image_metrics.h"
#include "path_tracer.h"
#include "raster_renderer.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

void closedRoomIsDark(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    for (float thickness : {0.1f, 0.02f}) {
        const scenes::SceneGeometry s = scenes::twoRooms(thickness);
        render::PathTracerOptions o;
        o.width = o.height = 32;
        std::string error;
        auto pt = render::PathTracer::create(*td.device, s, o, &error);
        REQUIRE(pt);
        pt->addSamples(32);
        float largest = 0.0f;
        for (float v : pt->read(render::Aov::Combined).rgb) largest = std::max(largest, v);
        INFO("wall " << thickness << ": brightest pixel of the closed room " << largest);
        CHECK(largest == 0.0f);
        // ...while the sunlit room is lit.
        scenes::Camera inA{{0.5f, 1.6f, 2.0f}, {4.0f, 0.5f, 2.0f}, {0, 1, 0}, 75.0f};
        REQUIRE(pt->setCamera(inA, &error));
        pt->addSamples(8);
        double sum = 0.0;
        for (float v : pt->read(render::Aov::Combined).rgb) sum += v;
        CHECK(sum > 0.0);
    }
    REQUIRE_NO_MESSAGES(td);
}

void dynamicSceneMoves(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    scenes::SceneGeometry s = scenes::dynamicRoom();
    REQUIRE(s.animate);
    render::RasterOptions ro;
    ro.width = ro.height = 48;
    ro.lightSamples = 1;
    std::string error;
    auto r = render::RasterRenderer::create(*td.device, s, ro, &error);
    REQUIRE(r);
    r->render();
    s.animate(s, 3);
    REQUIRE(r->setScene(s, &error));
    r->render();
    const render::Image motion = r->readMotion(), albedo = r->read(render::Aov::Albedo);
    const glm::vec3 torusAlbedo = s.meshes[1].albedo;
    size_t torusPixels = 0, movingTorus = 0, stillElsewhere = 0, elsewhere = 0;
    for (uint32_t y = 0; y < 48; ++y)
        for (uint32_t x = 0; x < 48; ++x) {
            const float m = glm::length(glm::vec2(motion.at(x, y)));
            if (glm::length(albedo.at(x, y) - torusAlbedo) < 1e-3f) {
                torusPixels++;
                movingTorus += m > 1e-3f;
            } else if (glm::length(albedo.at(x, y) - s.meshes[0].albedo) < 1e-3f) {  // the room
                elsewhere++;
                stillElsewhere += m == 0.0f;
            }
        }
    INFO(torusPixels << " torus pixels, " << movingTorus << " with motion; " << stillElsewhere << " of " << elsewhere << " others still");
    CHECK(torusPixels > 20);
    CHECK(movingTorus == torusPixels);
    CHECK(elsewhere > 1000);
    CHECK(stillElsewhere == elsewhere);  // the room and the camera do not move
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("scenes: two-rooms' closed room gets no light at all", "[render]", closedRoomIsDark)
BACKEND_TEST("scenes: dynamic moves, and its motion vectors show it", "[render]", dynamicSceneMoves)

TEST_CASE("scenes: names and parameters", "[metrics]") {
    std::string error;
    CHECK(scenes::loadScene("two-rooms:0.05", &error).meshes.size() == 2);
    CHECK(scenes::loadScene("two-rooms:abc", &error).meshes.empty());
    CHECK(error.find("wall thickness") != std::string::npos);
    CHECK(scenes::loadScene("two-rooms:-1", &error).meshes.empty());
    CHECK(scenes::loadScene("two-roomsX", &error).meshes.empty());
    CHECK(!scenes::loadScene("atrium", &error).meshes.empty());
    const scenes::SceneGeometry corridor = scenes::loadScene("corridor", &error);  // single-sided walls, one lamp
    CHECK(corridor.triangleCount() == 22);
    CHECK(corridor.meshes.size() == 4);
    CHECK(scenes::loadScene("dynamic", &error).animate);
}

namespace {

void pointAndSpotLights(const std::string& backend) {
    // A plane (albedo 0.5) under a point light of intensity I at height h: the radiance straight below is
    // albedo / pi * I / h^2; under a spot light aimed away, zero. Both the path tracer (pixel centres) and
    // the fast path, against the formula.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    scenes::SceneGeometry s;
    s.meshes.push_back(groundPlane(50.0f, glm::vec3(0.5f)));
    s.instances.push_back({0, glm::mat4(1.0f)});
    const float h = 2.0f, intensity = 8.0f;
    scenes::PointLight point;
    point.position = {0.0f, h, 0.0f};
    point.intensity = glm::vec3(intensity);
    s.pointLights.push_back(point);
    scenes::PointLight spot;
    spot.position = {0.0f, 1.0f, 0.0f};
    spot.intensity = glm::vec3(100.0f);
    spot.direction = {0.0f, 1.0f, 0.0f};  // pointing up: lights nothing on the plane
    spot.innerConeRadians = 0.3f;
    spot.outerConeRadians = 0.4f;
    s.pointLights.push_back(spot);
    s.camera = {glm::vec3(0.0f, 5.0f, 0.001f), glm::vec3(0.0f), glm::vec3(0, 0, 1), 20.0f};
    s.computeBounds();
    const double expected = 0.5 / M_PI * intensity / (h * h);
    Pair both = makePair(td, s, 9, 16, 4, false);
    const glm::vec3 traced = both.tracer->read(render::Aov::Direct).at(4, 4), rastered = both.raster->read(render::Aov::Direct).at(4, 4);
    INFO("expected " << expected << ", path tracer " << traced.x << ", fast path " << rastered.x);
    CHECK(traced.x == Approx(expected).epsilon(1e-3));
    CHECK(rastered.x == Approx(expected).epsilon(1e-3));
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("scenes: point and spot lights against the inverse-square law", "[render]", pointAndSpotLights)

TEST_CASE("scenes: lights from a file", "[metrics]") {
    std::string error;
    const scenes::SceneGeometry s = scenes::loadModel("/usr/share/assimp/models/Collada/lights.dae", &error);
    INFO(error);
    REQUIRE(!s.meshes.empty());
    CHECK(s.pointLights.size() == 3);  // two point lights and a spot light
    CHECK(s.environment.sunIrradiance.x > 0.0f);  // and a directional light, as the sun
    bool spot = false;
    for (const auto& l : s.pointLights) spot |= l.outerConeRadians < 3.0f;
    CHECK(spot);
}

namespace {

void shadingNormals(const std::string& backend) {
    // A coarse sphere with vertex normals: both paths report the interpolated normal (equal per pixel
    // with centre-sampled camera rays), which differs from the flat normal of the same sphere without them.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto sphere = [](bool smooth) {
        scenes::SceneGeometry s;
        scenes::TriangleMesh m = scenes::icosphere(1);
        if (smooth) m.normals = m.positions;  // unit sphere: the position is the normal
        s.meshes.push_back(m);
        s.instances.push_back({0, glm::mat4(1.0f)});
        s.environment.skyRadiance = glm::vec3(1.0f);
        s.camera = {glm::vec3(0, 0, 4), glm::vec3(0), glm::vec3(0, 1, 0), 35.0f};
        s.computeBounds();
        return s;
    };
    Pair smooth = makePair(td, sphere(true), 48, 1, 1, false);
    const render::Image a = smooth.tracer->read(render::Aov::Normal), b = smooth.raster->read(render::Aov::Normal);
    const render::Image flat = traced(td, sphere(false), 48, 1, false)->read(render::Aov::Normal);
    size_t differ = 0, smoothVsFlat = 0, covered = 0;
    for (size_t p = 0; p < size_t(48) * 48; ++p) {
        const glm::vec3 na(a.rgb[3 * p], a.rgb[3 * p + 1], a.rgb[3 * p + 2]), nb(b.rgb[3 * p], b.rgb[3 * p + 1], b.rgb[3 * p + 2]);
        const glm::vec3 nf(flat.rgb[3 * p], flat.rgb[3 * p + 1], flat.rgb[3 * p + 2]);
        if (glm::length(na) < 0.5f) continue;  // sky
        covered++;
        differ += glm::length(na - nb) > 2e-3f;
        smoothVsFlat += glm::length(na - nf) > 1e-2f;
    }
    INFO(covered << " sphere pixels; " << differ << " differ between the paths; " << smoothVsFlat << " differ from flat shading");
    CHECK(covered > 400);
    CHECK(differ <= covered / 100);
    CHECK(smoothVsFlat > covered / 2);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("scenes: shading normals from vertex normals, the same in both paths", "[render]", shadingNormals)

TEST_CASE("scenes: emitting surfaces become GI's area lights", "[metrics]") {
    // Cornell's light is one quad (two triangles, a → b → c and a → c → d): one Rect light facing down, with the
    // quad's corners and area; the sun of the two rooms stays a directional light beside it.
    const render::GiLights cornell = render::giLightsOf(scenes::cornellBox());
    REQUIRE(cornell.emittersInLights);
    REQUIRE(cornell.lights.size() == 1);
    const gi::Light& l = cornell.lights[0];
    CHECK(l.type == gi::LightType::Rect);
    CHECK(l.color == glm::vec3(17.0f, 12.0f, 4.0f));
    CHECK(glm::length(glm::cross(l.edge0, l.edge1)) == Approx(130.0f * 105.0f));
    CHECK(glm::normalize(glm::cross(l.edge0, l.edge1)).y == Approx(-1.0f));
    CHECK(l.position.y == Approx(548.0f));
    // A triangle that pairs with no other stays a Triangle, placed by its instance.
    scenes::SceneGeometry one;
    scenes::TriangleMesh tri;
    tri.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    tri.indices = {0, 1, 2};
    tri.emission = glm::vec3(2.0f);
    one.meshes.push_back(tri);
    one.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5))});
    const render::GiLights single = render::giLightsOf(one);
    REQUIRE(single.lights.size() == 1);
    CHECK(single.lights[0].type == gi::LightType::Triangle);
    CHECK(single.lights[0].position == glm::vec3(0, 0, 5));
    // More emitting triangles than gi::kMaxLights: none are given, the relight rays take the emission at their hits.
    scenes::SceneGeometry sphere = emittingSphere(0.5f, 1.0f);
    const render::GiLights many = render::giLightsOf(sphere);
    CHECK_FALSE(many.emittersInLights);
    CHECK(many.lights.empty());
}
