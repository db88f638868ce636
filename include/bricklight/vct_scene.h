// Bricklight voxel cone tracing: meshes registered from CPU arrays or the application's GPU buffers and
// voxelized through the same draw records as the application's own draws (vct::Clipmap::voxelizationState),
// with our vertex shader — the convenience path for an application that does not write a voxelization vertex
// shader, as sdf::SdfScene is for the distance field — or through a compute pass that runs the same per-triangle
// and per-pixel code (Voxelizer::Compute). docs/vct.md, "Registered meshes".
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bricklight/vct.h"

namespace bricklight::vct {

// A mesh from CPU arrays, copied to the device at registration. Positions (and normals, optional) are three
// floats per vertex in the mesh's own space; three indices per triangle.
struct VoxelMeshArrays {
    const float* positions = nullptr;
    const float* normals = nullptr;  // optional: without them each triangle's own normal is used
    uint32_t vertexCount = 0;
    const uint32_t* indices = nullptr;
    uint32_t indexCount = 0;
    std::string name;
};

// A mesh in the application's buffers (Vertex / Index usage), drawn where it lies: three floats per position
// (and normal) at the given offsets and strides, 32-bit indices. The device cannot check their contents:
// `boundsMin`/`boundsMax` (the mesh's own space) are what culling uses, and triangles with non-finite vertices
// are dropped by the geometry shader. The buffers must outlive the mesh. The compute voxelizer reads them as
// read buffers: it takes a mesh whose three buffers also have the ShaderRead usage and whose strides are
// multiples of 4 (the offsets are already); other meshes are drawn whatever the voxelizer.
struct VoxelMeshBuffers {
    rhi::BufferHandle positions;
    uint64_t positionsOffset = 0;
    uint32_t positionsStride = 12;
    rhi::BufferHandle normals;  // optional
    uint64_t normalsOffset = 0;
    uint32_t normalsStride = 12;
    uint32_t vertexCount = 0;
    rhi::BufferHandle indices;
    uint64_t indicesOffset = 0;
    uint32_t indexCount = 0;
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};
    std::string name;
};

struct VoxelMeshHandle {
    uint32_t id = 0;
    explicit operator bool() const { return id != 0; }
};
struct VoxelInstanceHandle {
    uint32_t id = 0;
    explicit operator bool() const { return id != 0; }
};

struct VoxelInstanceDesc {
    VoxelMeshHandle mesh;
    glm::mat4 transform{1.0f};  // mesh space to world; finite and invertible
    VoxelMaterial material;
    // Handed to the material's blVoxelEmittance as BlVoxelFragment::user0 / user1 (e.g. albedo and emission).
    glm::vec4 user0{0.0f}, user1{0.0f};
};

// The slot our vertex shader's per-instance constants take (transform, normal matrix, user vectors): the
// material's emittance function may use constants slots 0 and 1 only.
constexpr uint8_t kVoxelSceneInstanceConstants = 2;

// How voxelize() writes the instances it does not cull.
enum class Voxelizer {
    // One voxelization draw per instance: our vertex shader, the clip-map's geometry shader and the material's
    // fragment shader.
    Draws,
    // One compute invocation per triangle and level (bricklight/voxelize_compute.glsl: the geometry stage's setup
    // and the fragment body in a loop over the triangle's pixels), with the material's computeShader or
    // ours (opacity only). Triangles wider than ComputeVoxelizer::splitVoxels along any axis are appended to
    // a list that is then drawn (drawIndirect) through the draw path, so that each is voxelized exactly once.
    // An instance whose material has a fragmentShader but no computeShader, or whose mesh the compute pass
    // cannot read (VoxelMeshBuffers), is drawn as with Draws: nothing is silently lost.
    Compute,
};
struct ComputeVoxelizer {
    // The largest extent (finest-level voxels, any world axis) of a triangle voxelized in compute; wider ones
    // are drawn. An invocation loops over up to (splitVoxels + 2)² pixels at level 0, and a GPU's SIMD group
    // waits for its longest loop. 8: on lavapipe, 4 drew the atrium's many 4–8-voxel triangles at twice the
    // cost, and 8 to 1000 cost the same (docs/vct.md, "The compute voxelizer").
    float splitVoxels = 8.0f;
};

class VoxelScene {
public:
    // Null with *error if the device cannot create our vertex and compute shaders.
    static std::unique_ptr<VoxelScene> create(rhi::IDevice& device, Error* error = nullptr);
    ~VoxelScene();
    VoxelScene(const VoxelScene&) = delete;
    VoxelScene& operator=(const VoxelScene&) = delete;

    // A null handle with *error (naming the mesh) for empty or inconsistent arrays, non-finite values, indices
    // out of range, or buffers that are not live, lack the usage, or are too small for the counts.
    VoxelMeshHandle createMesh(const VoxelMeshArrays& mesh, Error* error = nullptr);
    VoxelMeshHandle createMesh(const VoxelMeshBuffers& mesh, Error* error = nullptr);
    // Refused while instances use the mesh.
    bool destroyMesh(VoxelMeshHandle mesh, Error* error = nullptr);

    // Each change of the instances marks the world boxes it touched (old and new places) dirty:
    // takeDirtyRegions() hands them to Clipmap::update's `invalidated`, so that a persistent clip-map rewrites
    // them. Refused (changing nothing) for an unknown mesh or instance, a bad transform or a bad material.
    VoxelInstanceHandle addInstance(const VoxelInstanceDesc& desc, Error* error = nullptr);
    bool setTransform(VoxelInstanceHandle instance, const glm::mat4& transform, Error* error = nullptr);
    bool removeInstance(VoxelInstanceHandle instance, Error* error = nullptr);
    std::vector<WorldBox> takeDirtyRegions();

    // Between Clipmap::update and finishVoxelization: voxelizes every instance whose world box meets this
    // update's rewrite regions, with its material's fragment shader (or, with Voxelizer::Compute, its compute
    // shader); `extra` (the emittance functions' own resources) is added to every draw and dispatch that runs
    // the material's shaders (ours, opacity only, declare none). False with *error, after voxelizing what it
    // could, if a material is refused or a dispatch fails (e.g. a computeShader that is not a compute shader:
    // that instance is then drawn).
    bool voxelize(Clipmap& clipmap, const rhi::Bindings& extra, Error* error = nullptr);
    uint32_t lastDrawCount() const { return lastDraws_; }  // instances the last voxelize() wrote (the rest were culled)
    uint32_t lastComputeCount() const { return lastComputes_; }  // of those, the instances voxelized in compute

    // Draws (the default) or Compute; takes effect at the next voxelize(). A negative or NaN split draws every
    // triangle.
    void setVoxelizer(Voxelizer voxelizer, const ComputeVoxelizer& options = {});
    Voxelizer voxelizer() const { return voxelizer_; }

    // The buffers the scene owns on the device: the meshes it uploaded (CPU arrays; an application's buffers are
    // its own) and the compute voxelizer's triangle lists.
    MemoryUse memoryUse() const;

private:
    struct Mesh;
    struct Instance;
    explicit VoxelScene(rhi::IDevice& device);  // in the .cpp, where Mesh and Instance are complete
    WorldBox worldBounds(const Mesh& mesh, const glm::mat4& transform) const;
    bool computeReadable(const Mesh& mesh) const;
    rhi::IDevice& device_;
    rhi::ShaderHandle vertex_, vertexFlat_;  // with and without normals
    rhi::ShaderHandle compute_;              // vct/voxelize_mesh.comp: the compute voxelizer, opacity only
    Voxelizer voxelizer_ = Voxelizer::Draws;
    ComputeVoxelizer computeOptions_;
    // The compute voxelizer's drawn-triangle lists: DrawIndexedArgs per instance, then each instance's indices.
    rhi::BufferHandle drawn_;
    uint64_t drawnBytes_ = 0;
    uint32_t lastComputes_ = 0;
    std::vector<std::unique_ptr<Mesh>> meshes_;
    std::vector<std::unique_ptr<Instance>> instances_;
    std::vector<WorldBox> dirty_;
    uint32_t nextId_ = 1;
    uint32_t lastDraws_ = 0;
};

}  // namespace bricklight::vct
