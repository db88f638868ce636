// Scene geometry for the examples, tests and benchmark: built-in procedural scenes (the Cornell box from
// its published measurements, a ~1M-triangle instanced field) and model files through assimp. Plain CPU
// data: meshes with a base colour and emission, placed by instances.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bricklight::scenes {

struct TriangleMesh {
    std::string name;
    std::vector<float> positions;   // xyz per vertex
    std::vector<uint32_t> indices;  // 3 per triangle
    glm::vec3 albedo{0.8f};
    glm::vec3 emission{0.0f};
    uint32_t triangleCount() const { return uint32_t(indices.size() / 3); }
};

struct MeshInstance {
    uint32_t mesh = 0;
    glm::mat4 transform{1.0f};
};

struct SceneGeometry {
    std::string name;
    std::vector<TriangleMesh> meshes;
    std::vector<MeshInstance> instances;
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};  // world bounds of all instances
    uint64_t triangleCount() const;              // over instances
    void computeBounds();
};

// Cornell's published box, in millimetres (about 556 x 548.8 x 559.2; open at z = 0).
SceneGeometry cornellBox();
// About `targetTriangles` triangles: a tessellated ground and rows of instanced spheres and tori.
SceneGeometry proceduralField(uint32_t targetTriangles);
// A torus of about `triangles` triangles (the benchmark's moving dynamic object).
TriangleMesh torus(float majorRadius, float minorRadius, uint32_t triangles);
// OBJ, glTF, PLY, FBX... through assimp, node transforms applied. Empty scene and `error` set on failure.
SceneGeometry loadModel(const std::string& path, std::string* error);
// A built-in scene by name ("cornell", "field"), or a model file.
SceneGeometry loadScene(const std::string& nameOrPath, std::string* error);

}  // namespace bricklight::scenes
