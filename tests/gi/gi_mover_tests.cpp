// GI follows a mover (issue: movers cost what they change, part 4): a green box on the floor of a room lit from
// the ceiling bleeds green onto the floor around it. It stands at A long enough for GI to converge, then
// jumps to B (a rigid dynamic instance of the distance field, composited from its mover grid). The green the
// floor receives on each side is compared with the path tracer's at the same positions, a stated number of
// frames after the jump — and with a renderer that saw the box at B only: A's side must have lost it (no ghost),
// B's gained as much as the fresh renderer's after as many frames.
#include <cmath>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "backend_test.h"
#include "path_tracer.h"
#include "raster_renderer.h"
#include "reference_cache.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

constexpr uint32_t kSize = 64;
constexpr uint32_t kSpp = 256;
constexpr uint32_t kFramesAfterMove = 16;

const glm::vec3 kA(-1.3f, 0.0f, 0.6f), kB(1.3f, 0.0f, 0.6f);

// The bare dynamic room, its light fixed in the middle of the ceiling, and the green box (dynamic) at `at`.
scenes::SceneGeometry greenBoxRoom(glm::vec3 at) {
    scenes::SceneGeometry room = scenes::dynamicRoom({false, false});
    room.animate = nullptr;
    room.meshes.erase(room.meshes.begin() + 1);  // no torus
    room.instances.erase(room.instances.begin() + 1);
    room.instances[1].mesh = 1;
    room.instances[1].transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 2.95f, 0.6f));
    room.instances[1].dynamic = false;
    room.meshes[1].emission = glm::vec3(30.0f);  // white: on the white room, green in the light is the box's
    scenes::TriangleMesh box;
    box.name = "green box";
    box.albedo = glm::vec3(0.1f, 0.85f, 0.1f);
    scenes::addBox(box, {-0.35f, 0.0f, -0.35f}, {0.35f, 0.8f, 0.35f});
    room.meshes.push_back(box);
    scenes::MeshInstance mover;
    mover.mesh = uint32_t(room.meshes.size() - 1);
    mover.transform = glm::translate(glm::mat4(1.0f), at);
    mover.dynamic = true;
    room.instances.push_back(mover);
    room.camera = {glm::vec3(0.0f, 2.4f, -2.6f), glm::vec3(0.0f, 0.0f, 0.9f), glm::vec3(0, 1, 0), 70.0f};
    room.computeBounds();
    return room;
}

// The green the floor receives (G − (R + B) / 2 of the indirect light, where positive) on a ring of floor around
// A and around B (0.45–0.9 m from the box's centre), pixels that see the box itself left out (`albedo`).
struct GreenSides {
    double a = 0.0, b = 0.0;
};
GreenSides greenSides(const scenes::Camera& camera, const render::Image& indirect, const render::Image& albedo) {
    GreenSides g;
    const glm::vec3 forward = glm::normalize(camera.at - camera.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up)), up = glm::cross(right, forward);
    const float tanHalf = std::tan(glm::radians(camera.verticalFovDegrees) * 0.5f);
    for (uint32_t y = 0; y < indirect.height; ++y)
        for (uint32_t x = 0; x < indirect.width; ++x) {
            const float sx = (2.0f * (float(x) + 0.5f) / float(indirect.width) - 1.0f) * tanHalf;
            const float sy = (1.0f - 2.0f * (float(y) + 0.5f) / float(indirect.height)) * tanHalf;
            const glm::vec3 d = forward + sx * right + sy * up;
            if (d.y >= 0.0f) continue;
            const glm::vec3 floor = camera.eye + d * (-camera.eye.y / d.y);
            const glm::vec3 seen = albedo.at(x, y);
            if (seen.g > seen.r + 0.2f) continue;  // the box
            const glm::vec3 c = indirect.at(x, y);
            const double green = std::max(0.0, double(c.g) - 0.5 * double(c.r + c.b));
            for (int side = 0; side < 2; ++side) {
                const float r = glm::length(glm::vec2(floor.x, floor.z) - glm::vec2(side ? kB.x : kA.x, side ? kB.z : kA.z));
                if (r > 0.45f && r < 0.9f) (side ? g.b : g.a) += green;
            }
        }
    return g;
}

void giFollowsMover(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    scenes::SceneGeometry atA = greenBoxRoom(kA), atB = greenBoxRoom(kB);
    const Reference tracedA = pathTraced(td, atA, kSize, kSpp), tracedB = pathTraced(td, atB, kSize, kSpp);
    auto sides = [&](const render::Image& indirect, const Reference& sameScene) {
        return greenSides(atA.camera, indirect, sameScene.read(render::Aov::Albedo));
    };
    const GreenSides refA = sides(tracedA.read(render::Aov::IndirectDiffuse), tracedA);
    const GreenSides refB = sides(tracedB.read(render::Aov::IndirectDiffuse), tracedB);
    auto sideA = [](const GreenSides& g) { return g.a; };
    auto sideB = [](const GreenSides& g) { return g.b; };
    auto r = sdfGiRenderer(td, atA, kSize);
    std::string error;
    frames(td, *r, 48);
    const GreenSides before = sides(r->read(render::Aov::IndirectDiffuse), tracedA);
    REQUIRE(r->setScene(atB, &error));
    std::ostringstream track;
    GreenSides after;
    for (uint32_t f = 1; f <= kFramesAfterMove; ++f) {
        frames(td, *r, 1);
        after = sides(r->read(render::Aov::IndirectDiffuse), tracedB);
        track << " " << f << ": " << sideA(after) / sideB(refB) << ", " << sideB(after) / sideB(refB) << ";";
    }
    // A renderer that saw the box at B only, as many frames: what the moving one should show.
    auto still = sdfGiRenderer(td, atB, kSize);
    frames(td, *still, kFramesAfterMove);
    const GreenSides fresh = sides(still->read(render::Aov::IndirectDiffuse), tracedB);
    frames(td, *still, 48);
    const GreenSides settled = sides(still->read(render::Aov::IndirectDiffuse), tracedB);
    REQUIRE_NO_MESSAGES(td);
    INFO(backend << ": green on the floor around A and B, as fractions of the path tracer's around the box: before the move A "
                 << sideA(before) / sideA(refA) << ", B " << sideB(before) / sideA(refA) << "; the renderer that saw B only: A "
                 << sideA(settled) / sideB(refB) << ", B " << sideB(settled) / sideB(refB) << " (B after " << kFramesAfterMove << " frames: "
                 << sideB(fresh) / sideB(refB) << "; the path tracer: A "
                 << sideA(refB) / sideB(refB) << "); frames after the move (A, B):" << track.str());
    // Before: GI bleeds the green at A as the path tracer does.
    CHECK(sideA(before) > 0.5 * sideA(refA));
    CHECK(sideA(before) < 1.5 * sideA(refA));
    CHECK(sideB(settled) > 0.5 * sideB(refB));
    CHECK(sideB(settled) < 1.5 * sideB(refB));
    // kFramesAfterMove frames after: A has no more green than the still renderer (no ghost: measured within 1 % of
    // B's green from the 9th frame on, both backends; since the probes' parallax test 4–6 % below it, nearer the path
    // tracer's), nor less than half the path tracer's there, and B has gained most of what a renderer that saw the
    // box there from its first frame has after as many frames (measured 0.73 of it; docs/gi.md, *Movers*, says
    // what is known of the rest).
    CHECK(sideA(after) < sideA(settled) + 0.05 * sideB(settled));
    CHECK(sideA(after) > 0.5 * sideA(refB));
    CHECK(sideB(after) > 0.6 * sideB(fresh));
}

}  // namespace

BACKEND_TEST("gi follows a moving object's colour bleeding within 16 frames, against the path tracer", "[gi]", giFollowsMover)
