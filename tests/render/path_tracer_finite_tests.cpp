// The path tracer never lets a non-finite sample into its image (issue 36): scenes made to provoke one — an emitter
// with a black base colour, coincident and degenerate triangles, walls meeting in grazing corners, single-sided
// walls, specular layers seen and lit head-on (where a cosine a rounding above 1 once sent a negative base to the
// Schlick term's pow: NaN, about one sample in six million on a corridor) — traced with many samples on both
// backends: every pixel of every AOV finite and no sample left out as non-finite.
#include <cmath>

#include "backend_test.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

scenes::TriangleMesh quad(const std::string& name, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 albedo) {
    scenes::TriangleMesh m;
    m.name = name;
    m.positions = {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, d.x, d.y, d.z};
    m.indices = {0, 1, 2, 0, 2, 3};
    m.albedo = albedo;
    m.specular = true;  // materials from files have one: the GGX lobe and its Schlick terms are evaluated
    m.roughness = 0.3f;
    return m;
}

// An L-shaped corridor of single-sided walls (no thickness) lit only by a black emitter around the corner, with
// a copy of one wall coincident with it, the emitter touching the end wall and the floor (grazing corners), and
// degenerate triangles (a repeated vertex, three collinear ones) in the light's way. `tilt` turns the whole scene
// about the camera so that the walls seen head-on are not axis-aligned (their cosines round differently).
scenes::SceneGeometry corridor(float tilt) {
    scenes::SceneGeometry s;
    const float h = 2.5f;
    const glm::vec3 white(0.75f), red(0.75f, 0.1f, 0.1f);
    auto add = [&](scenes::TriangleMesh m) { s.meshes.push_back(std::move(m)); };
    for (const glm::vec4& r : {glm::vec4(0, 2, 0, 10), glm::vec4(0, 2, -2, 0), glm::vec4(2, 10, -2, 0)}) {
        add(quad("floor", {r.x, 0, r.w}, {r.y, 0, r.w}, {r.y, 0, r.z}, {r.x, 0, r.z}, white));
        add(quad("ceiling", {r.x, h, r.z}, {r.y, h, r.z}, {r.y, h, r.w}, {r.x, h, r.w}, white));
    }
    add(quad("wall x=0", {0, 0, -2}, {0, 0, 10}, {0, h, 10}, {0, h, -2}, white));
    add(quad("wall x=2", {2, 0, 10}, {2, 0, 0}, {2, h, 0}, {2, h, 10}, white));
    add(quad("end wall", {10, 0, -2}, {0, 0, -2}, {0, h, -2}, {10, h, -2}, red));
    add(quad("end wall, coincident copy", {10, 0, -2}, {0, 0, -2}, {0, h, -2}, {10, h, -2}, white));
    add(quad("wall z=0", {2, 0, 0}, {10, 0, 0}, {10, h, 0}, {2, h, 0}, white));
    add(quad("wall x=10", {10, 0, 0}, {10, 0, -2}, {10, h, -2}, {10, h, 0}, white));
    add(quad("back wall", {0, 0, 10}, {2, 0, 10}, {2, h, 10}, {0, h, 10}, white));
    // The emitter (facing -x, black base colour) touches the floor and the end wall.
    scenes::TriangleMesh light = quad("emitter", {9.9f, 0, -2}, {9.9f, h * 0.8f, -2}, {9.9f, h * 0.8f, -0.2f}, {9.9f, 0, -0.2f}, glm::vec3(0.0f));
    light.emission = glm::vec3(60, 54, 44);
    add(light);
    scenes::TriangleMesh degenerate;
    degenerate.name = "degenerate";
    degenerate.positions = {5, 1, -1, 5, 1, -1, 5, 2, -1.5f, 4, 0.5f, -0.5f, 5, 1, -1, 6, 1.5f, -1.5f};
    degenerate.indices = {0, 1, 2, 3, 4, 5};
    degenerate.albedo = white;
    add(degenerate);
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), tilt, glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f)));
    for (uint32_t i = 0; i < s.meshes.size(); ++i) s.instances.push_back({i, turn});
    const glm::vec3 eye(1.0f, 1.25f, 9.0f), at(1.0f, 1.25f, -1.0f);
    s.camera = {glm::vec3(turn * glm::vec4(eye, 1.0f)), glm::vec3(turn * glm::vec4(at, 1.0f)), glm::vec3(turn * glm::vec4(0, 1, 0, 0)),
                50.0f};
    s.computeBounds();
    return s;
}

void everySampleFinite(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    // Odd sizes and pixel centres: the centre pixel looks along the camera axis, head-on at the end wall.
    constexpr uint32_t kSize = 33, kSpp = 512;
    uint64_t nonFinite = 0;
    for (float tilt : {0.0f, 0.37f, 1.1f}) {
        for (bool jitter : {false, true}) {
            auto pt = traced(td, corridor(tilt), kSize, kSpp, jitter);
            nonFinite += pt->samplesNonFinite();
            for (render::Aov aov : {render::Aov::Combined, render::Aov::Direct, render::Aov::IndirectDiffuse}) {
                const render::Image img = pt->read(aov);
                INFO("tilt " << tilt << (jitter ? ", jittered" : ", pixel centres") << ", AOV " << render::aovName(aov));
                CHECK(allFinite(img.rgb));
            }
        }
    }
    INFO(backend << ": " << nonFinite << " of " << 6 * kSize * kSize * kSpp << " samples non-finite");
    CHECK(nonFinite == 0);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("path tracer: no sample turns infinite or NaN on scenes made to provoke it", "[render]", everySampleFinite)
