// Bricklight sparse brick distance fields: cascades of 64³ voxels around a point the application moves
// (usually the camera); every voxel within reach of a triangle holds a brick of 8³ distance samples
// ("brixels") in one shared R8 atlas. Built on the GPU from triangle meshes through rhi::IDevice records;
// traced from shaders with the public include "bricklight/trace.glsl". See docs/sdf.md.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bricklight/errors.h"
#include "bricklight/memory_use.h"
#include "bricklight/rhi.h"

namespace bricklight::sdf {

constexpr uint32_t kMaxCascades = 16;
constexpr uint32_t kCascadeResolution = 64;  // voxels per axis of every cascade
constexpr uint32_t kBrickResolution = 8;     // brixels per axis; the 8 samples span the voxel (7 intervals)
// Distances are exact (point-triangle) up to this many brixel intervals (voxel/7) from a surface and
// saturate there. The stored value is min(distance, band): a conservative field, exact near surfaces.
constexpr float kDistanceBandBrixels = 2.0f;

// Handles are never reused within one SdfScene.
struct MeshHandle {
    uint32_t id = 0;
    explicit operator bool() const { return id != 0; }
};
struct InstanceHandle {
    uint32_t id = 0;
    explicit operator bool() const { return id != 0; }
};

struct Budgets {
    // Triangles transformed into the world per update (the triangle scratch holds this many).
    uint32_t maxTrianglesPerUpdate = 2u << 20;
    // Triangle-voxel references per update (16 bytes of scratch each).
    uint32_t maxReferencesPerUpdate = 8u << 20;
    // Voxels (re)built per update; bounds the bricks allocated per update. The default builds all of 16
    // cascades in one update.
    uint32_t maxVoxelsPerUpdate = kMaxCascades * kCascadeResolution * kCascadeResolution * kCascadeResolution;
    // Rebuild regions (jobs) per update.
    uint32_t maxJobsPerUpdate = 4096;
};

struct SceneDesc {
    uint32_t cascadeCount = 8;          // 1..16; cascade i has voxels of finestVoxelSize * 2^i
    float finestVoxelSize = 0.0f;       // world units, > 0 (see suggestVoxelSize)
    uint32_t atlasBricksPerAxis = 64;   // the atlas is (8n)³ R8_UNORM holding n³ bricks; 64 = 512³, 2^18 bricks
    uint32_t maxInstances = 65536;
    uint32_t maxBoundsOverlays = 256;   // boxes drawn by the debug view
    Budgets budgets;
    std::string debugName = "sdf";
    // Rigid movers at their footprint's cost: a dynamic instance of a mesh from CPU arrays, opaque, under a
    // transform without shear or non-uniform scale, is composited from a grid of its mesh's nearest triangles
    // built once per mesh and scale (docs/sdf.md, *Mover grids*) instead of re-voxelizing its triangles. Its
    // samples are then the exact distance to the nearest of the triangles nearest to the 27 grid points
    // around each (never nearer than exact; farther only where a surface curves within a grid cell); false
    // re-voxelizes every mover (exact everywhere, cost ~ its triangles).
    bool moverGrids = true;
    // Receives the builder's own messages (bad meshes, instances, budgets); stderr when empty. GPU-side
    // messages come through the device's callback.
    rhi::ErrorCallback errorCallback;
};

// A finest voxel size that makes the coarsest of `cascadeCount` cascades cover a box of `extent`
// (the largest side of the scene bounds), with 64 voxels per cascade side.
float suggestVoxelSize(float extent, uint32_t cascadeCount);

// Mesh from CPU arrays: copied into device buffers at creation.
struct MeshArrays {
    const float* positions = nullptr;  // xyz per vertex
    uint32_t vertexCount = 0;
    const uint32_t* indices = nullptr;  // 3 per triangle
    uint32_t indexCount = 0;
    std::string name;
};

enum class PositionFormat : uint8_t { Float3, Half4 };

// Mesh in the application's own GPU buffers (skinned or procedurally animated geometry): read by the
// GPU at every update that needs it, so the app may rewrite the positions between updates. Buffers need
// BufferUsage::ShaderRead. Offsets and the stride must be multiples of 4 bytes (2 for 16-bit indices).
// The local bounds are the app's promise: triangles outside them are dropped (and counted in stats).
struct MeshBuffers {
    rhi::BufferHandle vertexBuffer;
    uint64_t vertexOffset = 0;
    uint32_t vertexStride = 12;
    PositionFormat positionFormat = PositionFormat::Float3;
    uint32_t vertexCount = 0;
    rhi::BufferHandle indexBuffer;
    uint64_t indexOffset = 0;
    rhi::IndexFormat indexFormat = rhi::IndexFormat::U32;
    uint32_t triangleCount = 0;
    glm::vec3 boundsMin{0.0f};
    glm::vec3 boundsMax{0.0f};
    std::string name;
};

// How a surface looks, kept by the field per brick (the surface-area-weighted mean of the materials of the
// triangles in the brick; docs/sdf.md, "Surface materials"), for light the camera never saw. Linear values:
// albedo in [0, 1], emitted radiance >= 0.
struct SurfaceMaterial {
    glm::vec3 albedo{0.8f};
    glm::vec3 emission{0.0f};
};

struct InstanceDesc {
    MeshHandle mesh;
    glm::mat4 transform{1.0f};  // affine (last row 0,0,0,1)
    // Static instances persist until moved or removed (a move rebuilds their old and new regions from every
    // static instance there). Dynamic ones are rebuilt from their own triangles over the static field at every
    // update in which they may have changed: moved, or their mesh is in the application's buffers (deforming).
    bool dynamic = false;
    uint32_t maxCascade = kMaxCascades - 1;  // keeps small props out of coarse cascades
    // Alpha-tested geometry (grass and leaf cards, fences): the field is built on the whole triangles, as for
    // any instance, and the bricks that hold these surfaces are flagged so that a trace reports hits there as
    // BlSdfHit::alphaTested (per 4³ cell of the brick, leaving out cells that opaque surfaces also reach).
    // A tracer that knows the surfaces' coverage (gi::GiContext's alpha cache, docs/gi.md "Foliage") goes on
    // past the cut-out parts; others see the cards as solid. Fixed at registration.
    bool alphaTested = false;
    // The instance's material (one per instance; fixed at registration). None: the field holds no material
    // for its surfaces (blSdfBrickMaterial reads unknown there).
    std::optional<SurfaceMaterial> material;
};

// GPU counters of one update, read back without stalling (a few updates late).
struct Stats {
    uint64_t update = 0;             // the update these counters belong to (0 = none yet)
    uint32_t bricksCapacity = 0;
    uint32_t bricksFree = 0;         // after that update
    uint32_t bricksUsed = 0;
    uint32_t bricksAllocated = 0;    // by that update
    uint32_t bricksFreed = 0;
    uint32_t trianglesProcessed = 0;
    uint32_t trianglesRejected = 0;  // NaN/inf positions, indices out of range, outside the declared bounds
    uint32_t referencesProcessed = 0;
    uint32_t voxelsBuilt = 0;        // voxels that got a brick or were found empty
    uint32_t voxelsDeferredGpu = 0;  // voxels left unbuilt because the references or the brick pool ran out
    uint32_t bricksSplit = 0;        // bricks whose many references the brick pass split over several groups
};

// Work done or deferred by the latest update(), known on the CPU at once.
struct UpdateReport {
    uint64_t update = 0;
    uint32_t cascadesChanged = 0;  // bit mask
    uint32_t jobs = 0;
    uint32_t voxels = 0;           // voxels scheduled for (re)building
    uint32_t instancesGathered = 0;
    uint32_t trianglesGathered = 0;
    uint32_t jobsDeferred = 0;     // over a budget: carried to the next update
    uint32_t voxelsDeferred = 0;
    uint32_t jobsRetried = 0;      // re-queued because an earlier update reported GPU overflow
    // Of the above, the overlay: the footprints of dynamic instances, rebuilt from their triangles alone over
    // the static field kept there (docs/sdf.md, *Update model*).
    uint32_t overlayJobs = 0;
    uint32_t overlayVoxels = 0;
    uint32_t overlayTrianglesGathered = 0;
    uint32_t moverGridInstances = 0;  // of the overlay's instances, those composited from mover grids
    uint32_t moverGridsBuilt = 0;     // mover grids built by this update (a mesh or scale seen first)
};

using MemoryUse = bricklight::MemoryUse;  // bricklight/memory_use.h

enum class DebugMode : uint32_t { Distance, Normal, Iterations, BrickId, CascadeId, Uvw };

struct DebugViewDesc {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};  // depth [0,1] (GLM_FORCE_DEPTH_ZERO_TO_ONE style), any handedness
    rhi::TextureHandle output;   // 2D RGBA8_UNORM with Storage usage
    DebugMode mode = DebugMode::Normal;
    uint32_t startCascade = 0;
    uint32_t endCascade = kMaxCascades - 1;
    float tMin = 0.0f;
    float tMax = 1e30f;
    bool showCascadeBounds = false;
    bool showInstanceBounds = false;
};

// Where traceBindings() puts the field's resources; the including shader uses the same numbers
// (BL_SDF_ATLAS_SLOT and BL_SDF_READ_BUFFER_BASE in trace.glsl).
struct TraceSlots {
    uint8_t atlasTexture = 15;   // BL_TEXTURE slot
    uint8_t readBufferBase = 4;  // four consecutive BL_READ_BUFFER slots
};

// CPU copy of the decoded field, for tests and tools (blocking read-back).
struct FieldSnapshot {
    static constexpr uint32_t kEmpty = 0xFFFFFFFEu;
    static constexpr uint32_t kUnbuilt = 0xFFFFFFFFu;
    static constexpr uint32_t kNoBase = 0xFFFFFFFCu;
    struct Cascade {
        glm::ivec3 origin{0};  // world voxel coordinates of logical voxel (0,0,0)
        float voxelSize = 0.0f;
        std::vector<uint32_t> brickMap;  // physical (toroidal) order
        // Same order: where dynamic instances' distances are composited into the live brick, the brick (or
        // kEmpty) of the static geometry alone, kept for the next update; kNoBase elsewhere.
        std::vector<uint32_t> baseMap;
    };
    std::vector<Cascade> cascades;
    uint32_t atlasBricksPerAxis = 0;
    std::vector<uint8_t> atlas;           // (8n)³ bytes
    std::vector<uint32_t> brickAabbs;     // per brick: tight box (18 bits), kAabbAlphaTested; kAabbNone
    // Per brick, two words: bit (z·4 + y)·4 + x set where an opaque (not alpha-tested) surface reaches that
    // 4³ cell of the voxel. Meaningful for bricks flagged kAabbAlphaTested.
    std::vector<uint32_t> brickOpaqueCells;
    // Per brick, two words: the surface material's albedo as RGBA8 (alpha 255: known, 0: no instance with a
    // material reaches the brick) and its emission as RGB9E5 (bricklight/rgb9e5.glsl).
    std::vector<uint32_t> brickMaterials;
    static constexpr uint32_t kAabbAlphaTested = 1u << 30;

    // Brick id, kEmpty or kUnbuilt of a logical voxel (0..63 per axis).
    uint32_t voxelState(uint32_t cascade, glm::ivec3 logical) const;
    // Stored sample (0..255, 255 = at or beyond the band) of brixel `b` (0..7 per axis) of a brick.
    uint8_t brixel(uint32_t brick, glm::ivec3 b) const;
    // Distance (world units) at a lattice sample: `logical` voxel, brixel b; band if the voxel is empty;
    // negative if the voxel is unbuilt.
    float sampleDistance(uint32_t cascade, glm::ivec3 logical, glm::ivec3 b) const;
};

class SdfScene {
public:
    // Null (and a message through the device's error callback and `error`) if the description is invalid or the
    // device lacks what the builder needs.
    static std::unique_ptr<SdfScene> create(rhi::IDevice& device, const SceneDesc& desc, Error* error = nullptr);
    virtual ~SdfScene() = default;

    // Geometry. Errors name the object and the problem, and change nothing.
    virtual MeshHandle createMesh(const MeshArrays& mesh) = 0;
    virtual MeshHandle createMesh(const MeshBuffers& mesh) = 0;
    virtual bool destroyMesh(MeshHandle mesh) = 0;  // fails while instances use it
    virtual InstanceHandle addInstance(const InstanceDesc& instance) = 0;
    virtual bool setTransform(InstanceHandle instance, const glm::mat4& transform) = 0;
    virtual bool removeInstance(InstanceHandle instance) = 0;

    // Moves the cascades' centre, rebuilds what changed, and records all work through the device. After it
    // every cascade is current, except work over a budget (reported, and done by later updates).
    virtual UpdateReport update(const glm::vec3& center) = 0;
    // Drops all bricks and rebuilds everything at the next update.
    virtual void invalidateAll() = 0;

    // What a record that traces the field must bind (merged into the caller's bindings), and the
    // constants a caller needs none of: everything is in the bound buffers.
    virtual void traceBindings(rhi::Bindings& bindings, TraceSlots slots = {}) const = 0;
    virtual bool debugView(const DebugViewDesc& desc) = 0;
    // Per brick (uint32 each, brick capacity entries): the voxel that owns it, as cascade << 24 | allocation
    // generation << 18 | physical voxel index, or 0xFFFFFFFF for a brick never allocated. The generation
    // counts the brick's allocations (mod 64): a brick whose entry changes was freed and reallocated, even
    // where it went back to the same voxel (a rebuilt region's bricks are handed out again in any order),
    // and caches keyed by brick id (the GI's) compare entries to know what to forget.
    virtual rhi::BufferHandle brickOwnerBuffer() const = 0;
    virtual uint32_t brickCapacity() const = 0;

    virtual Stats latestStats() const = 0;
    virtual MemoryUse memoryUse() const = 0;
    virtual const SceneDesc& desc() const = 0;
    virtual glm::ivec3 cascadeOrigin(uint32_t cascade) const = 0;  // world voxel coordinates
    virtual float cascadeVoxelSize(uint32_t cascade) const = 0;
    virtual FieldSnapshot readField() = 0;  // blocking; for tests and tools
    virtual const Error& lastError() const = 0;  // the latest error of this scene (code None if none)
    // Every distinct message so far, with how often it was reported (each reaches the callback once).
    virtual std::vector<Diagnostic> diagnostics() const = 0;
    // update() calls so far (GI warns when it is dispatched on a scene never updated).
    virtual uint64_t updateCount() const = 0;
    // Where the latest update() changed geometry, in world units: the bounds before and after of every instance
    // added, moved or removed, and of every dynamic instance rebuilt (moved or deforming). GI refreshes its
    // light there (docs/gi.md, *Movers*).
    struct ChangedBox {
        glm::vec3 min{0.0f}, max{0.0f};
    };
    virtual const std::vector<ChangedBox>& latestChanges() const = 0;
    // Expires when the scene is destroyed: objects that follow the scene (a gi::GiContext) check it, so that
    // destroying the scene first is a clear error on their next call, never a crash.
    virtual std::weak_ptr<const void> lifetimeToken() const = 0;
};

}  // namespace bricklight::sdf
