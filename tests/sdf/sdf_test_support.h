// Shared by the SDF tests: the CPU reference (exact point-triangle distances and ray-triangle hits over a uniform grid),
// and a scene loader that puts a SceneGeometry into an SdfScene.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bricklight/sdf.h"
#include "scene_geometry.h"
#include "test_device.h"

namespace bricklight::sdftest {

using testing::makeDevice;
using testing::TestDevice;

// Exact geometry of a scene in world space (double precision), with a uniform grid for queries.
class Reference {
public:
    explicit Reference(const scenes::SceneGeometry& scene, double cellSize);
    size_t triangleCount() const { return tris_.size() / 3; }
    // Distance to the nearest triangle, or `limit` if none is nearer than `limit`.
    double distance(const glm::dvec3& p, double limit) const;
    // Nearest hit along a ray (t > tMin) within tMax; returns false on a miss. cosine = |n . d| at the hit.
    bool intersect(const glm::dvec3& origin, const glm::dvec3& direction, double tMin, double tMax, double* t,
                   double* cosine) const;
    const std::vector<glm::dvec3>& triangles() const { return tris_; }

private:
    std::vector<glm::dvec3> tris_;
    glm::dvec3 lo_, hi_;
    double cell_;
    glm::ivec3 dims_;
    std::vector<uint32_t> cellStart_, cellTriangles_;
};

double pointTriangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

struct LoadedScene {
    std::unique_ptr<sdf::SdfScene> scene;
    std::vector<sdf::MeshHandle> meshes;
    std::vector<sdf::InstanceHandle> instances;
};
// Meshes from CPU arrays, one instance per scene instance (alpha-tested where the mesh is).
LoadedScene loadIntoSdf(rhi::IDevice& device, const scenes::SceneGeometry& geometry, const sdf::SceneDesc& desc);
// Every mesh of `geometry` in `scene` (from CPU arrays), in order.
std::vector<sdf::MeshHandle> createMeshes(sdf::SdfScene& scene, const scenes::SceneGeometry& geometry);
// A description whose finest voxel puts the model 36 voxels across, with a 32³-brick atlas; the builder's
// messages go to the device's message list.
sdf::SceneDesc modelSceneDesc(const scenes::SceneGeometry& geometry, uint32_t cascades, TestDevice& td);

// Repository test models (Debian's assimp-testmodels).
std::string testModelPath(const std::string& relative);

// Compares the decoded fields of two scenes of equal descriptions voxel by voxel and brixel by brixel;
// returns the number of differing voxels (state) and the largest brixel difference (0..255).
struct FieldDifference {
    uint64_t voxelsCompared = 0;
    uint64_t stateMismatches = 0;
    uint32_t maxBrixelDifference = 0;
    uint64_t brixelsDiffering = 0;
    std::string firstMismatch;
};
FieldDifference compareFields(const sdf::FieldSnapshot& a, const sdf::FieldSnapshot& b);

}  // namespace bricklight::sdftest
