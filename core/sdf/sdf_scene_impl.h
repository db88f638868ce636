// The SdfScene implementation, split by concept:
//   sdf_scene.cpp      creation, resources, capability checks, memory, stats read-back, snapshot
//   sdf_geometry.cpp   meshes and instances (validation, bounds, dirty regions)
//   sdf_jobs.cpp       CPU planning of an update: scrolling slabs, dirty boxes -> jobs, budgets
//   sdf_update.cpp     the build passes as records
//   sdf_debug_view.cpp the debug view pass and trace bindings
#pragma once

#include <deque>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "../common/diagnostic_log.h"
#include "bricklight/sdf.h"
#include "sdf_layout.h"

namespace bricklight::sdf::detail {

struct Mesh {
    std::string name;
    bool owned = false;  // buffers created by the scene (from CPU arrays)
    rhi::BufferHandle vertexBuffer, indexBuffer;
    uint64_t vertexOffset = 0, indexOffset = 0;
    uint32_t vertexStride = 12;
    PositionFormat positionFormat = PositionFormat::Float3;
    uint32_t vertexCount = 0;
    rhi::IndexFormat indexFormat = rhi::IndexFormat::U32;
    uint32_t triangleCount = 0;
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};  // local
    uint32_t users = 0;
};

struct WorldBox {
    glm::vec3 min{0.0f}, max{0.0f};
};

struct Instance {
    MeshHandle mesh;
    glm::mat4 transform{1.0f};
    bool dynamic = false;
    uint32_t maxCascade = 0;
    bool alphaTested = false;
    std::optional<SurfaceMaterial> material;
    WorldBox bounds;       // of the current transform
    WorldBox builtBounds;  // what the field holds of it (dynamic: last update)
    glm::mat4 builtTransform{1.0f};  // dynamic: the transform the field holds it at
    bool built = false;
    int32_t moverGrid = -1;  // this update: the mover grid it is composited from (index in moverGrids_), or none
};

// A mesh's grid of nearest triangles at one scale (mover_grid.glsl), one level per cascade.
struct MoverGrid {
    uint32_t mesh = 0;
    float scale = 1.0f;
    uint32_t firstTriangle = 0;  // in moverGridData_, in triangles (12 words)
    uint32_t firstLevelRow = 0;  // in moverGridTable_
    struct Level {
        glm::vec3 origin{0.0f};  // object space
        float spacing = 0.0f;
        glm::uvec3 dims{0u};
        uint32_t firstKey = 0;  // word in moverGridData_
    };
    std::vector<Level> levels;
};

// A rebuild region: world voxel coordinates of one cascade, [min, max).
struct Job {
    uint32_t cascade = 0;
    glm::ivec3 min{0}, max{0};
    bool invalidated = false;  // its voxels were already made UNBUILT when it was first deferred
    uint64_t voxels() const {
        glm::ivec3 s = max - min;
        return uint64_t(s.x) * uint64_t(s.y) * uint64_t(s.z);
    }
};

// One round of building: jobs and the instances whose triangles they need.
struct Round {
    std::vector<Job> jobs;
    std::vector<uint32_t> instances;  // ids to gather
    uint32_t triangles = 0;  // gathered triangles, then mover grid chunks (moverChunks of them)
    uint64_t voxels = 0;
    uint32_t moverChunks = 0;
    uint32_t movers = 0;  // instances composited from mover grids
};

// What update() decided to do, before recording. Full jobs build the static field from the static
// instances; then the overlay (the old and new footprints of the dynamic instances) is built from the dynamic
// instances alone, over the static field kept aside there (its base bricks).
struct Plan {
    Round full;
    Round overlay;
    std::vector<Job> invalidateOnly;  // deferred: their voxels become UNBUILT now (no stale bricks)
    uint32_t changedCascades = 0;     // scrolled or with jobs: their trees are rebuilt
};

struct InFlightStats {
    uint64_t update = 0;
    uint64_t voxels = 0;
    uint64_t ticket = 0;
    std::vector<Job> jobs;  // re-queued if the GPU reports deferred voxels
};

class SdfSceneImpl final : public SdfScene {
public:
    SdfSceneImpl(rhi::IDevice& device, const SceneDesc& desc)
        : device_(device), desc_(desc), log_("sdf '" + desc.debugName + "': ") {}
    ~SdfSceneImpl() override;
    bool init(Error* error);

    MeshHandle createMesh(const MeshArrays& mesh) override;
    MeshHandle createMesh(const MeshBuffers& mesh) override;
    bool destroyMesh(MeshHandle mesh) override;
    InstanceHandle addInstance(const InstanceDesc& instance) override;
    bool setTransform(InstanceHandle instance, const glm::mat4& transform) override;
    bool removeInstance(InstanceHandle instance) override;

    UpdateReport update(const glm::vec3& center) override;
    void invalidateAll() override;

    void traceBindings(rhi::Bindings& bindings, TraceSlots slots) const override;
    bool debugView(const DebugViewDesc& desc) override;
    rhi::BufferHandle brickOwnerBuffer() const override { return brickOwners_; }
    uint32_t brickCapacity() const override;

    Stats latestStats() const override { return stats_; }
    MemoryUse memoryUse() const override;
    const SceneDesc& desc() const override { return desc_; }
    glm::ivec3 cascadeOrigin(uint32_t cascade) const override;
    float cascadeVoxelSize(uint32_t cascade) const override;
    FieldSnapshot readField() override;
    const Error& lastError() const override { return log_.lastError(); }
    std::vector<Diagnostic> diagnostics() const override { return log_.diagnostics(); }
    std::weak_ptr<const void> lifetimeToken() const override { return alive_; }
    uint64_t updateCount() const override { return updateIndex_; }
    const std::vector<ChangedBox>& latestChanges() const override { return changes_; }

private:
    bool fail(ErrorCode code, const std::string& message);  // reports, returns false
    float voxelSize(uint32_t cascade) const;
    float band(uint32_t cascade) const;
    rhi::BufferHandle makeBuffer(const char* name, uint64_t size, uint32_t usage, const void* data = nullptr);

    // sdf_geometry.cpp
    bool checkTransform(const glm::mat4& m, const std::string& what);
    WorldBox worldBounds(const Mesh& mesh, const glm::mat4& transform) const;
    void markDirty(const WorldBox& box, uint32_t maxCascade);

    // sdf_jobs.cpp
    void scrollCascades(const glm::vec3& center);
    Plan planUpdate(UpdateReport& report);
    bool clipToCascade(Job& job) const;
    uint32_t trianglesFor(const Job& job, bool dynamic, std::vector<char>& chosen, std::vector<uint32_t>& picked) const;
    void planRound(std::vector<Job> candidates, bool dynamic, Round& round, uint32_t& changedCascades);

    // sdf_mover_grids.cpp
    void prepareMoverGrids(UpdateReport& report);  // which movers use grids; builds the grids first needed
    uint32_t moverChunks(const Instance& inst, float tag, uint32_t materialTag, std::vector<glm::vec4>* out) const;
    void writeMovers(const Round& round, std::vector<glm::vec4>& chunks);  // the round's mover rows and chunks

    // sdf_update.cpp
    void recordGather(const Mesh& mesh, const glm::mat4& transform, uint32_t first, uint32_t maxCascade, bool alphaTested,
                      uint32_t materialTag, rhi::BufferHandle out, bool afterGather);
    void writeCascadeTable();
    void recordBuild(const Plan& plan);
    void writeJobTable(const std::vector<Job>& build, const std::vector<Job>& invalidateOnly);
    void recordRound(const Round& round);  // gather .. emit distances
    void recordTrees(uint32_t cascadeMask);
    void pollStats();

    rhi::IDevice& device_;
    SceneDesc desc_;
    bricklight::detail::DiagnosticLog log_;
    std::shared_ptr<const bool> alive_ = std::make_shared<const bool>(true);  // expires with the scene

    struct Shaders {
        rhi::ShaderHandle invalidate, gather, count, prepare, allocate, scatter, emit, finalizeSplit, resolve, prepareOverlay,
            resolveOverlay, treeBottom, treeTop, debug, buildMoverGrid;
    } shaders_;

    // Persistent resources.
    rhi::TextureHandle atlas_;
    rhi::SamplerHandle atlasSampler_;
    rhi::BufferHandle cascadeTable_, brickMaps_, trees_, brickAabbs_, brickOwners_, freeStack_, counters_, args_;
    rhi::BufferHandle voxelRefs_;
    rhi::BufferHandle baseMaps_;  // u32 per (cascade, voxel slot): the static field's brick under a composite
    // Bricks whose references the brick pass splits over several groups: their entries, chunks, minima
    // (+inf between rounds) and the chunks' material sums.
    rhi::BufferHandle splitBricks_, splitWork_, splitMinima_, splitMaterials_;
    // Per-update scratch, sized by the budgets.
    rhi::BufferHandle triangles_, references_, sortedReferences_, touched_, jobTable_, materialTable_, overlays_;
    uint32_t touchedCapacity_ = 0;
    // Mover grids: their triangles and keys, and the table of their levels and this round's movers.
    std::vector<MoverGrid> moverGrids_;
    rhi::BufferHandle moverGridData_, moverGridTable_;
    uint32_t moverLevelRows_ = 0;  // the table's first mover row (a multiple of 4)
    std::vector<glm::uvec4> moverLevelTable_;  // its level rows

    std::map<uint32_t, Mesh> meshes_;
    std::map<uint32_t, Instance> instances_;
    uint32_t nextMesh_ = 1, nextInstance_ = 1;

    struct CascadeState {
        glm::ivec3 origin{0};
        bool placed = false;
    };
    std::vector<CascadeState> cascades_;
    std::vector<WorldBox> dirtyBoxes_;
    std::vector<uint32_t> dirtyMaxCascade_;
    std::vector<Job> pending_;  // jobs carried over (budgets) or re-queued (GPU overflow)
    std::vector<ChangedBox> changes_;  // of the latest update

    uint64_t updateIndex_ = 0;
    std::deque<InFlightStats> inFlight_;
    Stats stats_;
    bool oversizeReported_ = false;
    // Voxels per update actually planned: halved when the GPU reports that references or bricks ran out
    // (so that retried work comes in smaller pieces and converges), doubled back after clean updates.
    uint64_t adaptiveVoxelLimit_ = 0;
    uint32_t retriedJobs_ = 0;
};

}  // namespace bricklight::sdf::detail
