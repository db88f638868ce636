// The "corridor" built-in scene: single-sided walls (no thickness) and light that reaches the camera only around
// a corner, the case of issue 36's corridor (an OBJ from outside the project) built in. An L-shaped corridor
// 2.5 m high and 2 m wide: the camera's arm runs along +z, the side arm leaves it along +x at its far end and
// ends in one emitting quad; the camera sees the corner, not the lamp. Every surface is a plane of two triangles
// (the field holds them as zero-thickness sheets); white (0.75) with one red wall. Units: metres.
#include "scene_geometry.h"

namespace bricklight::scenes {

SceneGeometry corridor() {
    SceneGeometry s;
    s.name = "corridor";
    const float h = 2.5f;
    // Footprint: the camera's arm x 0..2, z 0..8; the side arm x 2..8, z 6..8.
    TriangleMesh white;
    white.name = "walls";
    white.albedo = glm::vec3(0.75f);
    // A vertical wall from p to q (x, z), floor to ceiling, facing left of p → q seen from above (into the corridor:
    // every surface faces in, as the Cornell box's).
    auto wall = [&](TriangleMesh& m, glm::vec2 p, glm::vec2 q) {
        addQuad(m, {p.x, 0, p.y}, {q.x, 0, q.y}, {q.x, h, q.y}, {p.x, h, p.y});
    };
    wall(white, {0, 8}, {0, 0});  // the camera's arm, west
    wall(white, {8, 8}, {0, 8});  // north, both arms
    wall(white, {0, 0}, {2, 0});  // the camera's arm's south end
    wall(white, {2, 6}, {8, 6});  // the side arm, south
    // Floor (facing up) and ceiling (facing down), two quads each.
    addQuad(white, {0, 0, 0}, {0, 0, 8}, {2, 0, 8}, {2, 0, 0});
    addQuad(white, {2, 0, 6}, {2, 0, 8}, {8, 0, 8}, {8, 0, 6});
    addQuad(white, {0, h, 0}, {2, h, 0}, {2, h, 8}, {0, h, 8});
    addQuad(white, {2, h, 6}, {8, h, 6}, {8, h, 8}, {2, h, 8});
    TriangleMesh red;
    red.name = "red wall";
    red.albedo = glm::vec3(0.75f, 0.1f, 0.1f);
    wall(red, {2, 0}, {2, 6});  // the camera's arm, east: red up to the corner
    TriangleMesh end;
    end.name = "side arm's end";
    end.albedo = glm::vec3(0.75f);
    wall(end, {8, 6}, {8, 8});
    // The lamp: a quad 1.2 m × 1.0 m hung 5 cm in front of the side arm's end, facing back along the arm; it emits
    // and reflects nothing else (black albedo), as the OBJ's Kd 0 0 0.
    TriangleMesh lamp;
    lamp.name = "lamp";
    lamp.albedo = glm::vec3(0.0f);
    lamp.emission = glm::vec3(60.0f, 54.0f, 44.0f);
    addQuad(lamp, {7.95f, 0.9f, 6.4f}, {7.95f, 0.9f, 7.6f}, {7.95f, 1.9f, 7.6f}, {7.95f, 1.9f, 6.4f});
    for (TriangleMesh* m : {&white, &red, &end, &lamp}) {
        s.meshes.push_back(std::move(*m));
        s.instances.push_back({uint32_t(s.meshes.size() - 1), glm::mat4(1.0f)});
    }
    // In the camera's arm near its south end, looking towards the corner.
    s.camera = {glm::vec3(1.0f, 1.5f, 0.6f), glm::vec3(1.6f, 1.2f, 7.0f), glm::vec3(0, 1, 0), 60.0f};
    s.computeBounds();
    return s;
}

}  // namespace bricklight::scenes
