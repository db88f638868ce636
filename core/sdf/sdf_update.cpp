// One update as records: cascade table, job table, then the passes
//   full round:    invalidate -> gather (per static instance) -> count references -> prepare -> allocate ->
//                  prepare -> scatter -> emit distances -> resolve empty
//   overlay round: prepare overlay -> gather (per dynamic instance) -> ... -> emit distances (min with the
//                  base) -> resolve overlay
//   then tree bottom -> tree top
// with GPU-sized (indirect) dispatches after the counting pass, and a non-blocking read-back of the
// counters whose results arrive a few updates later (stats, and re-queuing work the GPU had to defer).
#include <cstring>

#include "sdf_scene_impl.h"

namespace bricklight::sdf::detail {

namespace {

using rhi::Access;

// Groups of 64 threads for n items: x up to kWideGroups, then y (shaders fold y back in).
void wideGroups(uint64_t items, uint32_t* x, uint32_t* y) {
    const uint64_t groups = (items + 63) / 64;
    *x = uint32_t(std::min<uint64_t>(groups, layout::kWideGroups));
    *y = uint32_t((groups + layout::kWideGroups - 1) / layout::kWideGroups);
}

struct Marker {
    rhi::IDevice& device;
    Marker(rhi::IDevice& d, const char* label) : device(d) { device.beginMarker(label); }
    ~Marker() { device.endMarker(); }
};

}  // namespace

void SdfSceneImpl::writeCascadeTable() {
    layout::GpuCascadeTable table{};
    table.header[0] = desc_.cascadeCount;
    table.header[1] = desc_.atlasBricksPerAxis;
    table.header[2] = brickCapacity();
    for (uint32_t c = 0; c < desc_.cascadeCount; ++c) {
        layout::GpuCascade& g = table.cascades[c];
        const glm::ivec3 o = cascades_[c].origin;
        g.origin[0] = o.x;
        g.origin[1] = o.y;
        g.origin[2] = o.z;
        g.origin[3] = cascades_[c].placed ? 1 : 0;
        const float vs = voxelSize(c);
        g.voxelSize[0] = vs;
        g.voxelSize[1] = 1.0f / vs;
        g.voxelSize[2] = layout::kHitEpsilonBrixels / 7.0f * vs;
        g.voxelSize[3] = band(c);
    }
    device_.writeBuffer(cascadeTable_, 0, &table, sizeof(table));
}

UpdateReport SdfSceneImpl::update(const glm::vec3& center) {
    UpdateReport report;
    report.update = ++updateIndex_;
    pollStats();
    if (!std::isfinite(center.x) || !std::isfinite(center.y) || !std::isfinite(center.z)) {
        fail(ErrorCode::InvalidArgument, "update: the centre is not finite; nothing done");
        return report;
    }
    std::vector<glm::ivec3> before;
    for (const CascadeState& c : cascades_) before.push_back(c.origin);
    scrollCascades(center);
    prepareMoverGrids(report);
    Plan plan = planUpdate(report);
    for (uint32_t c = 0; c < desc_.cascadeCount; ++c)
        if (cascades_[c].origin != before[c]) plan.changedCascades |= 1u << c;
    report.cascadesChanged = plan.changedCascades;
    report.jobsRetried = retriedJobs_;
    retriedJobs_ = 0;
    writeCascadeTable();
    if (!plan.full.jobs.empty() || !plan.overlay.jobs.empty() || !plan.invalidateOnly.empty()) recordBuild(plan);
    if (plan.changedCascades) recordTrees(plan.changedCascades);
    return report;
}

void SdfSceneImpl::invalidateAll() {
    for (uint32_t c = 0; c < desc_.cascadeCount; ++c)
        if (cascades_[c].placed) pending_.push_back({c, cascades_[c].origin, cascades_[c].origin + int(kCascadeResolution)});
}

// Job table: per-cascade bounds of the build jobs, then build jobs, then invalidate-only jobs.
void SdfSceneImpl::writeJobTable(const std::vector<Job>& build, const std::vector<Job>& invalidateOnly) {
    std::vector<layout::GpuInt4> table(layout::kJobTableHeadInts);
    for (uint32_t c = 0; c < kMaxCascades; ++c) {
        table[2 * c] = {{INT32_MAX, INT32_MAX, INT32_MAX, 0}};
        table[2 * c + 1] = {{INT32_MIN, INT32_MIN, INT32_MIN, 0}};
    }
    uint64_t voxels = 0;
    auto addJob = [&](const Job& j, bool isBuild) {
        table.push_back({{j.min.x, j.min.y, j.min.z, int32_t(j.cascade)}});
        const glm::ivec3 s = j.max - j.min;
        table.push_back({{s.x, s.y, s.z, int32_t(voxels)}});
        voxels += j.voxels();
        if (!isBuild) return;
        auto& lo = table[2 * j.cascade].v;
        auto& hi = table[2 * j.cascade + 1].v;
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], j.min[a]);
            hi[a] = std::max(hi[a], j.max[a]);
        }
        lo[3] = 1;
    };
    for (const Job& j : build) addJob(j, true);
    for (const Job& j : invalidateOnly) addJob(j, false);
    device_.writeBuffer(jobTable_, 0, table.data(), table.size() * sizeof(layout::GpuInt4));
}

// One thread per voxel of the job table's first `jobCount` jobs (`voxels` of them).
static void dispatchPerJobVoxel(rhi::IDevice& device, rhi::DispatchState& s, uint64_t voxels) {
    uint32_t gx, gy;
    wideGroups(voxels, &gx, &gy);
    if (voxels) device.dispatch(s, gx, gy, 1);
}

void SdfSceneImpl::recordBuild(const Plan& plan) {
    Marker all(device_, "sdf update");
    // Invalidate and prepare overlay: per job voxel, a state change that frees bricks and resets the counts.
    auto bindVoxelReset = [&](rhi::DispatchState& s) {
        s.bindings.readBuffers.push({0, jobTable_, {}});
        s.bindings.storageBuffers.push({0, brickMaps_, {}, Access::Atomic});
        s.bindings.storageBuffers.push({1, voxelRefs_, {}, Access::Write});
        s.bindings.storageBuffers.push({2, freeStack_, {}, Access::Write});
        s.bindings.storageBuffers.push({3, counters_, {}, Access::Atomic});
        s.bindings.storageBuffers.push({4, baseMaps_, {}, Access::Atomic});
    };
    device_.clearBuffer(counters_, {4, (layout::CounterCount - 1) * 4}, 0);  // all but the free count
    if (!plan.full.jobs.empty() || !plan.invalidateOnly.empty()) {
        writeJobTable(plan.full.jobs, plan.invalidateOnly);
        const uint64_t invalidated = plan.full.voxels + [&] {
            uint64_t v = 0;
            for (const Job& j : plan.invalidateOnly) v += j.voxels();
            return v;
        }();
        {
            Marker m(device_, "invalidate");
            struct { uint32_t jobCount, voxelCount, buildVoxelCount; } p{uint32_t(plan.full.jobs.size() + plan.invalidateOnly.size()),
                                                                        uint32_t(invalidated), uint32_t(plan.full.voxels)};
            rhi::DispatchState s;
            s.shader = shaders_.invalidate;
            s.label = "sdf invalidate jobs";
            s.bindings.constants.push(rhi::constants(0, p));
            bindVoxelReset(s);
            dispatchPerJobVoxel(device_, s, invalidated);
        }
        if (!plan.full.jobs.empty()) {
            recordRound(plan.full);
            Marker m(device_, "resolve empty");
            struct { uint32_t jobCount, voxelCount; } p{uint32_t(plan.full.jobs.size()), uint32_t(plan.full.voxels)};
            rhi::DispatchState s;
            s.shader = shaders_.resolve;
            s.label = "sdf resolve empty voxels";
            s.bindings.constants.push(rhi::constants(0, p));
            s.bindings.readBuffers.push({0, jobTable_, {}});
            s.bindings.storageBuffers.push({0, brickMaps_, {}, Access::Atomic});
            s.bindings.storageBuffers.push({1, counters_, {}, Access::Atomic});
            dispatchPerJobVoxel(device_, s, plan.full.voxels);
        }
    }
    if (!plan.overlay.jobs.empty()) {
        writeJobTable(plan.overlay.jobs, {});
        // The cursors of the full round start again (the stats counters add up over both rounds).
        device_.clearBuffer(counters_, {4 * layout::AllocCursor, 4 * (layout::SortedCursor - layout::AllocCursor + 1)}, 0);
        device_.clearBuffer(counters_, {4 * layout::SplitCursor, 4 * (layout::SplitWorkCursor - layout::SplitCursor + 1)}, 0);
        struct { uint32_t jobCount, voxelCount; } p{uint32_t(plan.overlay.jobs.size()), uint32_t(plan.overlay.voxels)};
        {
            Marker m(device_, "prepare overlay");
            rhi::DispatchState s;
            s.shader = shaders_.prepareOverlay;
            s.label = "sdf prepare overlay";
            s.bindings.constants.push(rhi::constants(0, p));
            bindVoxelReset(s);
            dispatchPerJobVoxel(device_, s, plan.overlay.voxels);
        }
        recordRound(plan.overlay);
        {
            Marker m(device_, "resolve overlay");
            rhi::DispatchState s;
            s.shader = shaders_.resolveOverlay;
            s.label = "sdf resolve overlay";
            s.bindings.constants.push(rhi::constants(0, p));
            s.bindings.readBuffers.push({0, jobTable_, {}});
            s.bindings.storageBuffers.push({0, brickMaps_, {}, Access::ReadWrite});
            s.bindings.storageBuffers.push({1, baseMaps_, {}, Access::ReadWrite});
            dispatchPerJobVoxel(device_, s, plan.overlay.voxels);
        }
    }
    InFlightStats f;
    f.update = updateIndex_;
    f.ticket = device_.requestReadback(counters_, 0, layout::CounterCount * 4);
    // Re-queued as full jobs if the GPU deferred voxels: an overlay voxel left unbuilt is built anew.
    f.jobs = plan.full.jobs;
    f.jobs.insert(f.jobs.end(), plan.overlay.jobs.begin(), plan.overlay.jobs.end());
    f.voxels = plan.full.voxels + plan.overlay.voxels;
    if (f.ticket) inFlight_.push_back(std::move(f));
}

// Appends a mesh's triangles, transformed, to `out` from triangle `first` on (gather_triangles.comp).
void SdfSceneImpl::recordGather(const Mesh& mesh, const glm::mat4& transform, uint32_t first, uint32_t maxCascade, bool alphaTested,
                                uint32_t materialTag, rhi::BufferHandle out, bool afterGather) {
    struct {
        float rows[3][4];
        float boundsMin[4], boundsMax[4];
        uint32_t vertex[4], index[4], misc[4];
    } p{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) p.rows[r][c] = transform[c][r];
    // Tolerance for the bounds check: positions read back as half floats round.
    const float extent = glm::length(mesh.boundsMax - mesh.boundsMin);
    const float tolerance = mesh.positionFormat == PositionFormat::Half4 ? 1e-3f * extent + 1e-3f : 1e-6f * extent;
    for (int a = 0; a < 3; ++a) {
        p.boundsMin[a] = mesh.boundsMin[a];
        p.boundsMax[a] = mesh.boundsMax[a];
    }
    p.boundsMin[3] = tolerance;
    p.vertex[0] = uint32_t(mesh.vertexOffset);
    p.vertex[1] = mesh.vertexStride;
    p.vertex[2] = mesh.positionFormat == PositionFormat::Float3 ? 0 : 1;
    p.vertex[3] = mesh.vertexCount;
    p.index[0] = uint32_t(mesh.indexOffset);
    p.index[1] = mesh.indexFormat == rhi::IndexFormat::U16 ? 0 : 1;
    p.index[2] = mesh.triangleCount;
    p.index[3] = first;
    p.misc[0] = maxCascade;
    p.misc[1] = alphaTested ? 1u : 0u;
    p.misc[2] = materialTag;
    rhi::DispatchState s;
    s.shader = shaders_.gather;
    s.label = "sdf gather triangles";
    // Disjoint ranges of the output; the first of a round waits for the previous round's readers.
    if (afterGather) s.flags = rhi::DispatchFlags::NoBarrierWithPreviousWriter;
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.readBuffers.push({0, mesh.vertexBuffer, {}});
    s.bindings.readBuffers.push({1, mesh.indexBuffer, {}});
    s.bindings.storageBuffers.push({0, out, {}, Access::Write});
    s.bindings.storageBuffers.push({1, counters_, {}, Access::Atomic});
    uint32_t gx, gy;
    wideGroups(mesh.triangleCount, &gx, &gy);
    device_.dispatch(s, gx, gy, 1);
}

void SdfSceneImpl::recordRound(const Round& round) {
    // What storing a brick writes (emit_brick.glsl), in emit distances and in finalize split bricks.
    auto bindBrickOutputs = [&](rhi::DispatchState& s) {
        s.bindings.storageBuffers.push({0, brickMaps_, {}, Access::Write});
        s.bindings.storageBuffers.push({1, brickAabbs_, {}, Access::ReadWrite});
        s.bindings.storageBuffers.push({2, freeStack_, {}, Access::Write});
        s.bindings.storageBuffers.push({3, counters_, {}, Access::Atomic});
        s.bindings.storageImages.push({0, rhi::wholeTexture(atlas_), Access::ReadWrite});
    };
    {
        // The gathered instances' materials, indexed by the tag gather gives their triangles (0: none).
        std::vector<glm::vec4> materials;
        for (uint32_t id : round.instances) {
            const Instance& inst = instances_.at(id);
            if (!inst.material) continue;
            materials.push_back(glm::vec4(inst.material->albedo, 1.0f));
            materials.push_back(glm::vec4(inst.material->emission, 0.0f));
        }
        if (!materials.empty()) device_.writeBuffer(materialTable_, 0, materials.data(), materials.size() * sizeof(glm::vec4));
    }
    uint32_t gx, gy;
    {
        Marker m(device_, "gather");
        uint32_t first = 0, materialTag = 0;
        bool afterGather = false;
        for (uint32_t id : round.instances) {
            const Instance& inst = instances_.at(id);
            const uint32_t tag = inst.material ? ++materialTag : 0u;
            if (inst.moverGrid >= 0) continue;  // composited from its grid: chunks below
            const Mesh& mesh = meshes_.at(inst.mesh.id);
            recordGather(mesh, inst.transform, first, inst.maxCascade, inst.alphaTested, tag, triangles_, afterGather);
            afterGather = true;
            first += mesh.triangleCount;
        }
        if (round.movers) {
            std::vector<glm::vec4> chunks;
            writeMovers(round, chunks);
            device_.writeBuffer(triangles_, uint64_t(first) * 48, chunks.data(), chunks.size() * sizeof(glm::vec4));
        }
    }
    {
        Marker m(device_, "count references");
        struct { uint32_t triangleCount, cascadeCount, maxReferences, touchedCapacity; } p{
            round.triangles, desc_.cascadeCount, desc_.budgets.maxReferencesPerUpdate, touchedCapacity_};
        rhi::DispatchState s;
        s.shader = shaders_.count;
        s.label = "sdf count references";
        s.bindings.constants.push(rhi::constants(0, p));
        s.bindings.readBuffers.push({0, triangles_, {}});
        s.bindings.readBuffers.push({1, cascadeTable_, {}});
        s.bindings.readBuffers.push({2, jobTable_, {}});
        s.bindings.storageBuffers.push({0, brickMaps_, {}, Access::Atomic});
        s.bindings.storageBuffers.push({1, voxelRefs_, {}, Access::Atomic});
        s.bindings.storageBuffers.push({2, references_, {}, Access::Write});
        s.bindings.storageBuffers.push({3, touched_, {}, Access::Write});
        s.bindings.storageBuffers.push({4, counters_, {}, Access::Atomic});
        s.bindings.storageBuffers.push({5, moverGridTable_, {}, Access::Read});
        s.bindings.storageBuffers.push({6, moverGridData_, {}, Access::Read});
        wideGroups(round.triangles, &gx, &gy);
        if (round.triangles) device_.dispatch(s, gx, gy, 1);
    }
    auto prepare = [&](uint32_t stage) {
        struct { uint32_t stage, maxReferences; } p{stage, desc_.budgets.maxReferencesPerUpdate};
        rhi::DispatchState s;
        s.shader = shaders_.prepare;
        s.label = stage == 0 ? "sdf prepare allocation" : "sdf commit allocation";
        s.bindings.constants.push(rhi::constants(0, p));
        s.bindings.storageBuffers.push({0, counters_, {}, Access::ReadWrite});
        s.bindings.storageBuffers.push({1, args_, {}, Access::Write});
        device_.dispatch(s, 1, 1, 1);
    };
    {
        Marker m(device_, "allocate bricks");
        prepare(0);
        rhi::DispatchState s;
        s.shader = shaders_.allocate;
        s.label = "sdf allocate bricks";
        s.bindings.storageBuffers.push({0, brickMaps_, {}, Access::ReadWrite});
        s.bindings.storageBuffers.push({1, voxelRefs_, {}, Access::Read});
        s.bindings.storageBuffers.push({2, touched_, {}, Access::ReadWrite});
        s.bindings.storageBuffers.push({3, counters_, {}, Access::Atomic});
        s.bindings.storageBuffers.push({4, freeStack_, {}, Access::Read});
        s.bindings.storageBuffers.push({5, brickOwners_, {}, Access::Write});
        s.bindings.storageBuffers.push({6, splitBricks_, {}, Access::Write});
        s.bindings.storageBuffers.push({7, splitWork_, {}, Access::Write});
        device_.dispatchIndirect(s, args_, layout::kArgsPerTouched64);
        prepare(1);
    }
    {
        Marker m(device_, "scatter references");
        rhi::DispatchState s;
        s.shader = shaders_.scatter;
        s.label = "sdf scatter references";
        s.bindings.readBuffers.push({0, references_, {}});
        s.bindings.readBuffers.push({1, voxelRefs_, {}});
        s.bindings.readBuffers.push({2, touched_, {}});
        s.bindings.readBuffers.push({3, counters_, {}});
        s.bindings.storageBuffers.push({0, sortedReferences_, {}, Access::Write});
        device_.dispatchIndirect(s, args_, layout::kArgsPerReference64);
    }
    {
        Marker m(device_, "emit distances");
        rhi::DispatchState s;
        s.shader = shaders_.emit;
        s.label = "sdf emit distances";
        s.bindings.readBuffers.push({0, triangles_, {}});
        s.bindings.readBuffers.push({1, sortedReferences_, {}});
        s.bindings.readBuffers.push({2, touched_, {}});
        s.bindings.readBuffers.push({3, cascadeTable_, {}});
        s.bindings.readBuffers.push({4, materialTable_, {}});
        s.bindings.readBuffers.push({5, baseMaps_, {}});
        s.bindings.readBuffers.push({6, splitBricks_, {}});
        s.bindings.readBuffers.push({7, splitWork_, {}});
        bindBrickOutputs(s);
        s.bindings.storageBuffers.push({4, splitMinima_, {}, Access::Atomic});
        s.bindings.storageBuffers.push({5, splitMaterials_, {}, Access::Write});
        s.bindings.storageBuffers.push({6, moverGridTable_, {}, Access::Read});
        s.bindings.storageBuffers.push({7, moverGridData_, {}, Access::Read});
        device_.dispatchIndirect(s, args_, layout::kArgsPerTouchedBrick);
    }
    {
        Marker m(device_, "finalize split bricks");
        rhi::DispatchState s;
        s.shader = shaders_.finalizeSplit;
        s.label = "sdf finalize split bricks";
        s.bindings.readBuffers.push({0, touched_, {}});
        s.bindings.readBuffers.push({1, cascadeTable_, {}});
        s.bindings.readBuffers.push({2, baseMaps_, {}});
        s.bindings.readBuffers.push({3, splitBricks_, {}});
        s.bindings.readBuffers.push({4, splitMaterials_, {}});
        bindBrickOutputs(s);
        s.bindings.storageBuffers.push({4, splitMinima_, {}, Access::ReadWrite});
        device_.dispatchIndirect(s, args_, layout::kArgsPerSplitBrick);
    }
}

void SdfSceneImpl::recordTrees(uint32_t mask) {
    Marker all(device_, "sdf trees");
    struct { uint32_t cascadeMask; } p{mask};
    rhi::DispatchState s;
    s.shader = shaders_.treeBottom;
    s.label = "sdf tree bottom";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.readBuffers.push({0, cascadeTable_, {}});
    s.bindings.readBuffers.push({1, brickMaps_, {}});
    s.bindings.readBuffers.push({2, brickAabbs_, {}});
    s.bindings.storageBuffers.push({0, trees_, {}, Access::Write});
    device_.dispatch(s, 4096 / 64, desc_.cascadeCount, 1);
    rhi::DispatchState top;
    top.shader = shaders_.treeTop;
    top.label = "sdf tree top";
    top.bindings.constants.push(rhi::constants(0, p));
    top.bindings.storageBuffers.push({0, trees_, {}, Access::ReadWrite});
    device_.dispatch(top, 1, desc_.cascadeCount, 1);
}

void SdfSceneImpl::pollStats() {
    while (!inFlight_.empty()) {
        uint32_t c[layout::CounterCount] = {};
        const rhi::ReadbackStatus status = device_.pollReadback(inFlight_.front().ticket, c);
        if (status == rhi::ReadbackStatus::Pending) return;
        InFlightStats f = std::move(inFlight_.front());
        inFlight_.pop_front();
        if (status != rhi::ReadbackStatus::Ready) continue;
        Stats s;
        s.update = f.update;
        s.bricksCapacity = brickCapacity();
        s.bricksFree = c[layout::FreeCount];
        s.bricksUsed = s.bricksCapacity - std::min(s.bricksCapacity, s.bricksFree);
        s.bricksAllocated = c[layout::BricksAllocated];
        s.bricksFreed = c[layout::BricksFreed];
        s.trianglesProcessed = c[layout::TrianglesProcessed];
        s.trianglesRejected = c[layout::TrianglesRejected];
        s.referencesProcessed = c[layout::RefsInUpdate];
        s.voxelsBuilt = c[layout::VoxelsBuilt];
        s.voxelsDeferredGpu = c[layout::VoxelsDeferred];
        s.bricksSplit = c[layout::BricksSplit];
        stats_ = s;
        // The GPU left voxels of these jobs unbuilt (references or bricks ran out): build them again.
        // While the pool is exhausted this retries every update; the stats say why.
        if (s.voxelsDeferredGpu) {
            for (Job j : f.jobs) {
                j.invalidated = true;  // built or UNBUILT now: no stale bricks
                pending_.push_back(j);
            }
            retriedJobs_ += uint32_t(f.jobs.size());
            adaptiveVoxelLimit_ = std::max<uint64_t>(1, f.voxels / 2);
        } else {
            adaptiveVoxelLimit_ = std::min<uint64_t>(desc_.budgets.maxVoxelsPerUpdate, adaptiveVoxelLimit_ * 2);
        }
    }
}

}  // namespace bricklight::sdf::detail
