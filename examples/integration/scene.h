// The application's own scene: a room open at the front, lit by a sun through a hole in its ceiling.
// Everything is a box (a unit cube with a transform), which the example hands twice to the GPU: once to
// its own raster pass (vertex, index and per-instance buffers) and once to Bricklight's distance field
// (one sdf mesh, one sdf instance per box). An engine does the same with its real meshes.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bricklight/rhi.h"
#include "bricklight/sdf.h"

namespace integration {

struct Box {
    std::string name;
    glm::mat4 transform{1.0f};  // maps the unit cube [-0.5, 0.5]³ into the world
    glm::vec3 albedo{0.75f};    // linear diffuse colour
    float roughness = 0.9f;     // perceptual
};

struct Sun {
    glm::vec3 direction{0.0f, 1.0f, 0.0f};  // unit, from a surface towards the sun (gi::Light's convention)
    glm::vec3 irradiance{0.0f};             // on a surface facing the sun
};

struct Camera {
    glm::vec3 eye{0.0f}, target{0.0f, 0.0f, -1.0f};
    float verticalFovDegrees = 60.0f;
    float nearPlane = 0.05f, farPlane = 100.0f;
};

struct Room {
    std::vector<Box> boxes;
    Sun sun;
    Camera camera;
};

Room buildRoom();

// The unit cube with one normal per face: 24 vertices of (position, normal), 36 indices.
struct CubeMesh {
    std::vector<float> vertices;  // 6 floats per vertex
    std::vector<uint32_t> indices;
};
CubeMesh unitCube();

// The room in the application's own GPU buffers, ready for its raster pass.
struct RoomBuffers {
    bricklight::rhi::BufferHandle vertices;   // CubeMesh::vertices
    bricklight::rhi::BufferHandle indices;    // CubeMesh::indices
    bricklight::rhi::BufferHandle instances;  // per box: 3 rows of its affine transform, then albedo + roughness
    uint32_t indexCount = 0;
    uint32_t instanceCount = 0;
};
bool uploadRoom(bricklight::rhi::IDevice& device, const Room& room, RoomBuffers* out, std::string* error);
void destroyRoom(bricklight::rhi::IDevice& device, RoomBuffers& buffers);

// Registers the room with the distance field: the cube once, then one static instance per box.
bool addRoomToField(bricklight::sdf::SdfScene& field, const Room& room, std::string* error);

// The exact answer the trace API should give for a shadow ray, from the boxes themselves: used by the
// checks to show that the composite's rays through the field agree with the geometry.
bool rayHitsAnyBox(const Room& room, const glm::vec3& origin, const glm::vec3& direction);

}  // namespace integration
