#include "scene.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace integration {

namespace {

Box box(const char* name, glm::vec3 min, glm::vec3 max, glm::vec3 albedo, float roughness = 0.9f) {
    Box b;
    b.name = name;
    b.transform = glm::scale(glm::translate(glm::mat4(1.0f), 0.5f * (min + max)), max - min);
    b.albedo = albedo;
    b.roughness = roughness;
    return b;
}

Box block(const char* name, glm::vec3 size, glm::vec3 centre, float yawDegrees, glm::vec3 albedo, float roughness) {
    Box b;
    b.name = name;
    b.transform = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), centre), glm::radians(yawDegrees), glm::vec3(0, 1, 0)), size);
    b.albedo = albedo;
    b.roughness = roughness;
    return b;
}

}  // namespace

Room buildRoom() {
    // Interior: x in [-2, 2], y in [0, 3], z in [-2, 2]; walls 0.2 thick; the front (z = 2) is open and the
    // camera looks in through it. Thick walls rather than single quads keep light from leaking through a
    // wall thinner than a voxel of the coarser cascades.
    const glm::vec3 white(0.75f, 0.75f, 0.72f), red(0.75f, 0.12f, 0.10f), green(0.12f, 0.60f, 0.15f);
    Room r;
    r.boxes.push_back(box("floor", {-2.2f, -0.2f, -2.2f}, {2.2f, 0.0f, 2.0f}, white));
    r.boxes.push_back(box("back wall", {-2.2f, 0.0f, -2.2f}, {2.2f, 3.0f, -2.0f}, white));
    r.boxes.push_back(box("left wall", {-2.2f, 0.0f, -2.0f}, {-2.0f, 3.0f, 2.0f}, red));
    r.boxes.push_back(box("right wall", {2.0f, 0.0f, -2.0f}, {2.2f, 3.0f, 2.0f}, green));
    // The ceiling: four slabs around a 1.4 x 1.4 hole at x in [-0.7, 0.7], z in [-1.4, 0].
    r.boxes.push_back(box("ceiling left", {-2.2f, 3.0f, -2.2f}, {-0.7f, 3.2f, 2.0f}, white));
    r.boxes.push_back(box("ceiling right", {0.7f, 3.0f, -2.2f}, {2.2f, 3.2f, 2.0f}, white));
    r.boxes.push_back(box("ceiling back", {-0.7f, 3.0f, -2.2f}, {0.7f, 3.2f, -1.4f}, white));
    r.boxes.push_back(box("ceiling front", {-0.7f, 3.0f, 0.0f}, {0.7f, 3.2f, 2.0f}, white));
    // Two blocks: one in the sun patch (it casts a shadow the checks look at), one in the shade.
    r.boxes.push_back(block("grey block", {0.6f, 0.6f, 0.6f}, {1.2f, 0.3f, 0.4f}, 25.0f, {0.7f, 0.7f, 0.7f}, 0.35f));
    r.boxes.push_back(block("blue block", {0.7f, 1.4f, 0.7f}, {-1.0f, 0.7f, -0.8f}, -15.0f, {0.15f, 0.25f, 0.7f}, 0.5f));

    // Steep enough that sunlight enters only through the hole: the patch it lights on the floor is the hole
    // moved by 3 * (direction.x, direction.z) / direction.y, i.e. x in [0.2, 1.6], z in [-0.8, 0.6].
    r.sun.direction = glm::normalize(glm::vec3(-0.3f, 1.0f, -0.2f));
    r.sun.irradiance = glm::vec3(6.0f, 5.6f, 5.0f);
    r.camera.eye = {0.0f, 1.5f, 3.0f};
    r.camera.target = {0.0f, 1.1f, -1.0f};
    r.camera.verticalFovDegrees = 65.0f;
    return r;
}

CubeMesh unitCube() {
    CubeMesh m;
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {-1.0f, 1.0f}) {
            glm::vec3 n(0.0f), u(0.0f), v(0.0f);
            n[axis] = sign;
            u[(axis + 1) % 3] = 1.0f;
            v[(axis + 2) % 3] = 1.0f;
            const uint32_t first = uint32_t(m.vertices.size() / 6);
            for (glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
                const glm::vec3 p = 0.5f * (n + c.x * u + c.y * v);
                m.vertices.insert(m.vertices.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
            }
            // Winding does not matter: the raster pass draws both sides (the depth test keeps the nearest).
            m.indices.insert(m.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
        }
    return m;
}

bool uploadRoom(bricklight::rhi::IDevice& device, const Room& room, RoomBuffers* out, std::string* error) {
    using namespace bricklight::rhi;
    const CubeMesh cube = unitCube();
    std::vector<glm::vec4> instances;
    for (const Box& b : room.boxes) {
        const glm::mat4 rows = glm::transpose(b.transform);  // GLM is column-major; the shader rebuilds it from rows
        instances.insert(instances.end(), {rows[0], rows[1], rows[2], glm::vec4(b.albedo, b.roughness)});
    }
    auto buffer = [&](const char* name, const void* data, size_t bytes, uint32_t usage) {
        BufferDesc d;
        d.size = bytes;
        d.usage = usage;
        d.debugName = name;
        return device.createBuffer(d, data);
    };
    out->vertices = buffer("room vertices", cube.vertices.data(), cube.vertices.size() * sizeof(float), BufferUsage::Vertex);
    out->indices = buffer("room indices", cube.indices.data(), cube.indices.size() * sizeof(uint32_t), BufferUsage::Index);
    out->instances = buffer("room instances", instances.data(), instances.size() * sizeof(glm::vec4), BufferUsage::Vertex);
    out->indexCount = uint32_t(cube.indices.size());
    out->instanceCount = uint32_t(room.boxes.size());
    if (out->vertices && out->indices && out->instances) return true;
    if (error) *error = "the device could not create the room's buffers (see its messages)";
    return false;
}

void destroyRoom(bricklight::rhi::IDevice& device, RoomBuffers& buffers) {
    for (bricklight::rhi::BufferHandle b : {buffers.vertices, buffers.indices, buffers.instances})
        if (b) device.destroy(b);
    buffers = {};
}

bool addRoomToField(bricklight::sdf::SdfScene& field, const Room& room, std::string* error) {
    // The field needs positions and triangles only: the same cube, without its normals.
    const CubeMesh cube = unitCube();
    std::vector<float> positions;
    for (size_t i = 0; i < cube.vertices.size(); i += 6) positions.insert(positions.end(), &cube.vertices[i], &cube.vertices[i + 3]);
    bricklight::sdf::MeshArrays arrays;
    arrays.positions = positions.data();
    arrays.vertexCount = uint32_t(positions.size() / 3);
    arrays.indices = cube.indices.data();
    arrays.indexCount = uint32_t(cube.indices.size());
    arrays.name = "unit cube";
    const bricklight::sdf::MeshHandle mesh = field.createMesh(arrays);  // copied to the GPU now
    if (!mesh) {
        if (error) *error = "the distance field rejected the cube: " + field.lastError().message;
        return false;
    }
    for (const Box& b : room.boxes) {
        bricklight::sdf::InstanceDesc instance;
        instance.mesh = mesh;
        instance.transform = b.transform;  // static: built once, rebuilt only if moved (setTransform)
        if (!field.addInstance(instance)) {
            if (error) *error = "the distance field rejected box '" + b.name + "': " + field.lastError().message;
            return false;
        }
    }
    return true;
}

bool rayHitsAnyBox(const Room& room, const glm::vec3& origin, const glm::vec3& direction) {
    for (const Box& b : room.boxes) {
        // In the box's own space the box is the unit cube: a slab test there.
        const glm::mat4 toLocal = glm::inverse(b.transform);
        const glm::vec3 o = glm::vec3(toLocal * glm::vec4(origin, 1.0f));
        const glm::vec3 d = glm::vec3(toLocal * glm::vec4(direction, 0.0f));
        float tNear = 0.0f, tFar = 1e30f;
        for (int a = 0; a < 3; ++a) {
            if (std::abs(d[a]) < 1e-12f) {
                if (o[a] < -0.5f || o[a] > 0.5f) tFar = -1.0f;
                continue;
            }
            float t0 = (-0.5f - o[a]) / d[a], t1 = (0.5f - o[a]) / d[a];
            if (t0 > t1) std::swap(t0, t1);
            tNear = std::max(tNear, t0);
            tFar = std::min(tFar, t1);
        }
        if (tNear <= tFar) return true;
    }
    return false;
}

}  // namespace integration
