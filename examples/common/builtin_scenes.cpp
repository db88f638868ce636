// The renderer's built-in test scenes beyond the Cornell box: the Cornell box with a glass sphere, the light-leak
// test, an outdoor-indoor courtyard, and an animated room. Units: metres (the Cornell box's: millimetres).
#include <cmath>
#include <numbers>
#include <glm/gtc/matrix_transform.hpp>

#include "scene_geometry.h"

namespace bricklight::scenes {

namespace {

uint32_t addMesh(SceneGeometry& s, TriangleMesh m) {
    s.meshes.push_back(std::move(m));
    const uint32_t i = uint32_t(s.meshes.size() - 1);
    s.instances.push_back({i, glm::mat4(1.0f)});
    return i;
}

TriangleMesh named(const char* name, glm::vec3 albedo) {
    TriangleMesh m;
    m.name = name;
    m.albedo = albedo;
    return m;
}

}  // namespace

SceneGeometry cornellGlass() {
    SceneGeometry s = cornellBox();
    s.name = "cornell-glass";
    // The sphere takes the short block's place (x 82..290, z 65..272), resting on the floor in front of the tall
    // block: through it the box is seen upside down, the red wall on its left and the green one on its right.
    const float radius = 100.0f;
    const glm::vec3 centre(200.0f, radius, 175.0f);
    TriangleMesh sphere = icosphere(3);  // 1280 triangles: enough for smooth refraction with its vertex normals
    sphere.name = "glass sphere";
    sphere.normals = sphere.positions;  // a unit sphere's normals are its positions
    for (size_t i = 0; i < sphere.positions.size(); ++i) sphere.positions[i] = centre[int(i % 3)] + radius * sphere.positions[i];
    sphere.transmission = 1.0f;
    sphere.ior = 1.5f;
    sphere.roughness = 0.1f;
    // Used only where the renderer draws the sphere opaque (without a clip-map to trace: docs/render.md).
    sphere.albedo = glm::vec3(0.9f);
    sphere.specular = true;
    for (size_t m = 0; m < s.meshes.size(); ++m)
        if (s.meshes[m].name == "short block") s.meshes[m] = std::move(sphere);
    s.computeBounds();
    return s;
}

SceneGeometry cornellMirror(float roughness) {
    SceneGeometry s = cornellBox();
    s.name = "cornell-mirror";
    // A polished metal floor: it shows the back wall and the blocks (on screen) and the box's open front and the
    // ceiling above the camera (off screen), the cases hybrid reflections split between the screen and the field.
    for (TriangleMesh& m : s.meshes)
        if (m.name == "floor") {
            m.albedo = glm::vec3(0.9f);
            m.metalness = 1.0f;
            m.roughness = roughness;
            m.specular = true;
        }
    return s;
}

SceneGeometry twoRooms(float t) {
    SceneGeometry s;
    s.name = "two-rooms";
    const float w = 0.2f;  // outer shell thickness
    const glm::vec3 white(0.8f);
    TriangleMesh shell = named("shell", white);
    const float east = 8.0f + t;
    addBox(shell, {-w, -w, -w}, {east + w, 0.0f, 4.0f + w});                 // floor
    addBox(shell, {-w, 0.0f, -w}, {0.0f, 3.0f, 4.0f + w});                    // west wall
    addBox(shell, {east, 0.0f, -w}, {east + w, 3.0f, 4.0f + w});              // east wall
    addBox(shell, {0.0f, 0.0f, -w}, {east, 3.0f, 0.0f});                      // south wall
    addBox(shell, {0.0f, 0.0f, 4.0f}, {east, 3.0f, 4.0f + w});                // north wall
    // Ceiling: room B closed; room A with an opening x 1.5..2.5, z 1.5..2.5.
    addBox(shell, {4.0f, 3.0f, -w}, {east + w, 3.0f + w, 4.0f + w});
    addBox(shell, {-w, 3.0f, -w}, {1.5f, 3.0f + w, 4.0f + w});
    addBox(shell, {2.5f, 3.0f, -w}, {4.0f, 3.0f + w, 4.0f + w});
    addBox(shell, {1.5f, 3.0f, -w}, {2.5f, 3.0f + w, 1.5f});
    addBox(shell, {1.5f, 3.0f, 2.5f}, {2.5f, 3.0f + w, 4.0f + w});
    addMesh(s, std::move(shell));
    TriangleMesh wall = named("shared wall", white);
    addBox(wall, {4.0f, 0.0f, 0.0f}, {4.0f + t, 3.0f, 4.0f});
    addMesh(s, std::move(wall));
    // The sun falls through the opening onto room A's floor next to the shared wall.
    s.environment = {glm::vec3(0.3f, 0.4f, 0.6f), glm::normalize(glm::vec3(-0.5f, 1.0f, 0.1f)), glm::vec3(5.0f)};
    s.camera = {glm::vec3(7.5f + t, 1.6f, 2.0f), glm::vec3(4.0f + t, 1.2f, 2.0f), glm::vec3(0, 1, 0), 75.0f};
    s.computeBounds();
    return s;
}

SceneGeometry atrium() {
    SceneGeometry s;
    s.name = "atrium";
    const glm::vec3 stone(0.62f, 0.55f, 0.45f);
    TriangleMesh ground = named("ground", glm::vec3(0.5f, 0.48f, 0.42f));
    addBox(ground, {-15.0f, -0.2f, -15.0f}, {15.0f, 0.0f, 15.0f});
    addMesh(s, std::move(ground));
    // Outer walls 6 m high around a 20 x 20 m court; a gallery roof 3 m wide at 5 m over the inner edge.
    TriangleMesh walls = named("walls", stone);
    addBox(walls, {-10.5f, 0.0f, -10.5f}, {10.5f, 6.0f, -10.0f});
    addBox(walls, {-10.5f, 0.0f, 10.0f}, {10.5f, 6.0f, 10.5f});
    addBox(walls, {-10.5f, 0.0f, -10.0f}, {-10.0f, 6.0f, 10.0f});
    addBox(walls, {10.0f, 0.0f, -10.0f}, {10.5f, 6.0f, 10.0f});
    addBox(walls, {-10.0f, 5.0f, -10.0f}, {10.0f, 5.4f, -7.0f});  // gallery roofs (the centre is open)
    addBox(walls, {-10.0f, 5.0f, 7.0f}, {10.0f, 5.4f, 10.0f});
    addBox(walls, {-10.0f, 5.0f, -7.0f}, {-7.0f, 5.4f, 7.0f});
    addBox(walls, {7.0f, 5.0f, -7.0f}, {10.0f, 5.4f, 7.0f});
    addMesh(s, std::move(walls));
    // Pillars every 2 m along the inner edge, with arches (semicircles of 12 segments) between them.
    TriangleMesh colonnade = named("colonnade", glm::vec3(0.75f, 0.72f, 0.66f));
    auto arch = [&](glm::vec3 a, glm::vec3 b) {
        const glm::vec3 mid = (a + b) * 0.5f, half = (b - a) * 0.5f;
        const float r = glm::length(half);
        for (int k = 0; k < 12; ++k) {
            const float t0 = std::numbers::pi_v<float> * float(k) / 12.0f, t1 = std::numbers::pi_v<float> * float(k + 1) / 12.0f;
            const glm::vec3 p0 = mid - half * std::cos(t0) + glm::vec3(0, 3.6f + r * std::sin(t0), 0);
            const glm::vec3 p1 = mid - half * std::cos(t1) + glm::vec3(0, 3.6f + r * std::sin(t1), 0);
            addBox(colonnade, glm::min(p0, p1) - glm::vec3(0.15f), glm::max(p0, p1) + glm::vec3(0.15f));
        }
    };
    for (int side = 0; side < 4; ++side)
        for (int k = 0; k <= 7; ++k) {
            const float u = -7.0f + 2.0f * float(k);
            glm::vec3 c = side == 0 ? glm::vec3(u, 0, -7) : side == 1 ? glm::vec3(u, 0, 7) : side == 2 ? glm::vec3(-7, 0, u) : glm::vec3(7, 0, u);
            addBox(colonnade, c + glm::vec3(-0.25f, 0.0f, -0.25f), c + glm::vec3(0.25f, 5.0f, 0.25f));
            if (k < 7) {
                const glm::vec3 next = side < 2 ? c + glm::vec3(2, 0, 0) : c + glm::vec3(0, 0, 2);
                arch(c + (next - c) * 0.125f, next - (next - c) * 0.125f);
            }
        }
    addMesh(s, std::move(colonnade));
    // A thin cloth hanging from the north gallery roof: one sheet of triangles, waved.
    TriangleMesh cloth = named("cloth", glm::vec3(0.7f, 0.12f, 0.1f));
    const int n = 24;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float x = -2.0f + 4.0f * float(i) / n, y = 5.0f - 3.5f * float(j) / n;
            const float z = 7.2f + 0.15f * std::sin(float(i) * 0.9f) * float(j) / n;
            cloth.positions.insert(cloth.positions.end(), {x, y, z});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = uint32_t(j * (n + 1) + i);
            cloth.indices.insert(cloth.indices.end(), {a, a + n + 1, a + 1, a + 1, a + n + 1, a + n + 2});
        }
    addMesh(s, std::move(cloth));
    s.environment = {glm::vec3(0.35f, 0.45f, 0.65f), glm::normalize(glm::vec3(0.5f, 0.8f, -0.35f)), glm::vec3(4.0f)};
    s.camera = {glm::vec3(-8.5f, 1.7f, -8.5f), glm::vec3(2.0f, 2.2f, 3.0f), glm::vec3(0, 1, 0), 70.0f};
    s.computeBounds();
    return s;
}

SceneGeometry dynamicRoom(DynamicRoomContent content) {
    SceneGeometry s;
    s.name = "dynamic";
    TriangleMesh room = named("room", glm::vec3(0.75f));
    addBox(room, {-3.2f, -0.2f, -3.2f}, {3.2f, 0.0f, 3.2f});
    addBox(room, {-3.2f, 3.0f, -3.2f}, {3.2f, 3.2f, 3.2f});
    addBox(room, {-3.2f, 0.0f, -3.2f}, {-3.0f, 3.0f, 3.2f});
    addBox(room, {3.0f, 0.0f, -3.2f}, {3.2f, 3.0f, 3.2f});
    addBox(room, {-3.0f, 0.0f, -3.2f}, {3.0f, 3.0f, -3.0f});
    addBox(room, {-3.0f, 0.0f, 3.0f}, {3.0f, 3.0f, 3.2f});
    addMesh(s, std::move(room));
    TriangleMesh object = torus(0.5f, 0.18f, 2000);
    object.name = "moving torus";
    object.albedo = glm::vec3(0.2f, 0.5f, 0.8f);
    addMesh(s, std::move(object));
    // The light: a small quad facing down, just under the ceiling.
    TriangleMesh light = named("moving light", glm::vec3(0.8f));
    light.positions = {-0.3f, 0.0f, -0.3f, -0.3f, 0.0f, 0.3f, 0.3f, 0.0f, 0.3f, 0.3f, 0.0f, -0.3f};
    light.indices = {0, 2, 1, 0, 3, 2};  // counter-clockwise seen from below: emits downwards
    light.emission = glm::vec3(30.0f, 27.0f, 22.0f);
    addMesh(s, std::move(light));
    s.instances[1].dynamic = s.instances[2].dynamic = true;
    // A crowd: 12 boxes of one mesh walking a circle on the floor (rigid movers).
    constexpr uint32_t kCrowd = 12;
    const uint32_t crowdFirst = uint32_t(s.instances.size());
    if (content.crowd) {
        TriangleMesh walker = named("crowd walker", glm::vec3(0.8f, 0.55f, 0.3f));
        addBox(walker, {-0.12f, 0.0f, -0.08f}, {0.12f, 0.45f, 0.08f});
        addMesh(s, std::move(walker));
        const uint32_t mesh = s.instances.back().mesh;
        for (uint32_t i = 1; i < kCrowd; ++i) s.instances.push_back({mesh, glm::mat4(1.0f)});
        for (uint32_t i = 0; i < kCrowd; ++i) s.instances[crowdFirst + i].dynamic = true;
    }
    // A deforming torus in a corner: its tube swells in a wave running round it (positions rewritten).
    const uint32_t deformingInstance = uint32_t(s.instances.size());
    TriangleMesh restShape;
    if (content.deforming) {
        TriangleMesh blob = torus(0.35f, 0.12f, 1500);
        blob.name = "deforming torus";
        blob.albedo = glm::vec3(0.8f, 0.2f, 0.15f);
        blob.deforming = true;
        blob.deformingBoundsMin = glm::vec3(-0.6f, -0.25f, -0.6f);
        blob.deformingBoundsMax = glm::vec3(0.6f, 0.25f, 0.6f);
        restShape = blob;
        addMesh(s, std::move(blob));
        s.instances.back().transform = glm::translate(glm::mat4(1.0f), glm::vec3(-2.2f, 0.35f, 2.0f));
        s.instances.back().dynamic = true;
    }
    s.animate = [content, crowdFirst, deformingInstance, restShape](SceneGeometry& g, uint32_t frame) {
        const float t = 0.1f * float(frame);
        g.instances[1].transform = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1.5f * std::cos(t), 0.7f, 1.5f * std::sin(t))),
                                               2.0f * t, glm::vec3(1.0f, 0.3f, 0.0f));
        g.instances[2].transform = glm::translate(glm::mat4(1.0f), glm::vec3(1.8f * std::sin(0.7f * t), 2.95f, -1.0f + std::cos(0.5f * t)));
        if (content.crowd)
            for (uint32_t i = 0; i < kCrowd; ++i) {
                const float a = 0.6f * t + 2.0f * glm::pi<float>() * float(i) / float(kCrowd);
                const float r = 2.3f + 0.25f * std::sin(1.3f * t + float(i));
                g.instances[crowdFirst + i].transform =
                    glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(r * std::cos(a), 0.0f, r * std::sin(a))), -a, glm::vec3(0, 1, 0));
            }
        if (content.deforming) {
            std::vector<float>& p = g.meshes[g.instances[deformingInstance].mesh].positions;
            p = restShape.positions;
            for (size_t v = 0; v < p.size(); v += 3) {
                // Around the ring's centre line: the tube's radius scaled by a wave along the ring.
                const float around = std::atan2(p[v + 2], p[v]);
                const glm::vec3 centre(0.35f * std::cos(around), 0.0f, 0.35f * std::sin(around));
                const float swell = 1.0f + 0.6f * std::max(0.0f, std::sin(3.0f * around - 2.0f * t));
                for (int k = 0; k < 3; ++k) p[v + size_t(k)] = centre[k] + (p[v + size_t(k)] - centre[k]) * swell;
            }
        }
    };
    s.animate(s, 0);
    s.camera = {glm::vec3(0.0f, 1.6f, -2.9f), glm::vec3(0.0f, 0.8f, 1.0f), glm::vec3(0, 1, 0), 75.0f};
    s.computeBounds();
    return s;
}

}  // namespace bricklight::scenes
