// Mover grids: a rigid dynamic instance at its footprint's cost (shaders/sdf/mover_grid.glsl). Per mesh and
// scale, built once: the mesh's triangles in object space and, per cascade, a lattice of the nearest triangle
// to each point. An update then composites the mover over the static field as the overlay does for any
// dynamic instance, but its references are a few chunks of voxels, not its triangles, and the brick pass
// evaluates at most 8 candidate triangles per sample.
#include <algorithm>
#include <cmath>

#include "sdf_scene_impl.h"

namespace bricklight::sdf::detail {

namespace {

// The factor by which a transform scales distances, if it scales them uniformly (rotations, mirrors, one scale
// and a translation); 0 for a shear or a non-uniform scale, which do not map distances.
float uniformScale(const glm::mat4& m) {
    const glm::vec3 x(m[0]), y(m[1]), z(m[2]);
    const float s = glm::length(x);
    if (!(s > 0.0f) || !std::isfinite(s)) return 0.0f;
    const float tolerance = 1e-4f * s;
    if (std::abs(glm::length(y) - s) > tolerance || std::abs(glm::length(z) - s) > tolerance) return 0.0f;
    if (std::abs(glm::dot(x, y)) > tolerance * s || std::abs(glm::dot(y, z)) > tolerance * s || std::abs(glm::dot(z, x)) > tolerance * s)
        return 0.0f;
    return s;
}

// The scale a mover's grid is built for: its transform's, on a ladder of 1024 steps per octave, so that the
// rounding of a rotating transform does not ask for a new grid every update. The grid's spacing is then off by
// at most 0.034 %; the distances are scaled by the transform's own factor.
float gridScale(const glm::mat4& m) {
    const float s = uniformScale(m);
    return s == 0.0f ? 0.0f : std::exp2(std::round(std::log2(s) * 1024.0f) / 1024.0f);
}

}  // namespace

void SdfSceneImpl::prepareMoverGrids(UpdateReport& report) {
    // The grid levels of a mesh at a scale, or none if a level would be over the sample budget.
    auto levelsFor = [&](const Mesh& mesh, float scale, std::vector<MoverGrid::Level>& levels) {
        uint64_t samples = 0;
        levels.clear();
        for (uint32_t c = 0; c < desc_.cascadeCount; ++c) {
            MoverGrid::Level l;
            l.spacing = voxelSize(c) / 7.0f / scale;
            l.origin = mesh.boundsMin - float(layout::kMoverMarginCells) * l.spacing;
            const glm::vec3 cells = glm::ceil((mesh.boundsMax - mesh.boundsMin) / l.spacing);
            if (glm::any(glm::greaterThan(cells, glm::vec3(4096.0f)))) return false;
            l.dims = glm::uvec3(cells) + 1u + 2u * uint32_t(layout::kMoverMarginCells);
            samples += uint64_t(l.dims.x) * l.dims.y * l.dims.z;
            if (samples > layout::kMoverMaxSamples) return false;
            levels.push_back(l);
        }
        return true;
    };
    auto find = [&](uint32_t mesh, float scale) -> int32_t {
        for (size_t g = 0; g < moverGrids_.size(); ++g)
            if (moverGrids_[g].mesh == mesh && moverGrids_[g].scale == scale) return int32_t(g);
        return -1;
    };
    // Which dynamic instances are rigid movers with a grid; the grids missing.
    std::vector<MoverGrid> wanted;
    bool missing = false;
    std::vector<MoverGrid::Level> levels;
    for (auto& [id, inst] : instances_) {
        inst.moverGrid = -1;
        if (!desc_.moverGrids || !inst.dynamic || inst.alphaTested) continue;
        const Mesh& mesh = meshes_.at(inst.mesh.id);
        // Meshes in the application's buffers may deform: re-voxelized.
        if (!mesh.owned || mesh.triangleCount == 0 || mesh.triangleCount >= layout::kMoverMaxTriangles) continue;
        const float scale = gridScale(inst.transform);
        if (scale == 0.0f) continue;
        bool listed = false;
        for (const MoverGrid& g : wanted) listed = listed || (g.mesh == inst.mesh.id && g.scale == scale);
        if (listed) continue;
        if (find(inst.mesh.id, scale) < 0) {
            if (!levelsFor(mesh, scale, levels)) continue;
            missing = true;
        }
        MoverGrid g;
        g.mesh = inst.mesh.id;
        g.scale = scale;
        wanted.push_back(g);
    }
    if (missing) {
        // A mesh or scale seen first: the grids are laid out again, those still wanted, and all built.
        uint64_t triangles = 0, levelRows = 0;
        for (MoverGrid& g : wanted) {
            g.firstTriangle = uint32_t(triangles);
            triangles += meshes_.at(g.mesh).triangleCount;
            g.firstLevelRow = uint32_t(levelRows);
            levelRows += 2ull * desc_.cascadeCount;
        }
        uint64_t words = triangles * 12;
        for (MoverGrid& g : wanted) {
            levelsFor(meshes_.at(g.mesh), g.scale, g.levels);
            for (MoverGrid::Level& l : g.levels) {
                l.firstKey = uint32_t(words);
                words += uint64_t(l.dims.x) * l.dims.y * l.dims.z;
            }
        }
        if (words >= (1ull << 32)) {
            fail(ErrorCode::OverBudget, "mover grids: more than 2^32 words in all; movers are re-voxelized");
            for (auto& [id, inst] : instances_) inst.moverGrid = -1;
            return;
        }
        if (moverGridData_) device_.destroy(moverGridData_);
        moverGridData_ = makeBuffer("moverGridData", std::max<uint64_t>(words, 4) * 4, rhi::BufferUsage::ShaderRead | rhi::BufferUsage::ShaderWrite);
        moverLevelRows_ = uint32_t((levelRows + 3) / 4 * 4);
        std::vector<glm::uvec4>& rows = moverLevelTable_;
        rows.assign(moverLevelRows_, glm::uvec4(0u));
        for (const MoverGrid& g : wanted)
            for (size_t c = 0; c < g.levels.size(); ++c) {
                const MoverGrid::Level& l = g.levels[c];
                glm::uvec4& r0 = rows[g.firstLevelRow + 2 * c];
                glm::uvec4& r1 = rows[g.firstLevelRow + 2 * c + 1];
                for (int a = 0; a < 3; ++a) r0[a] = std::bit_cast<uint32_t>(l.origin[a]);
                r0.w = std::bit_cast<uint32_t>(1.0f / l.spacing);
                r1 = glm::uvec4(l.dims, l.firstKey);
            }
        uint32_t dynamicCount = 0;
        for (const auto& [id, inst] : instances_) dynamicCount += inst.dynamic;
        const uint64_t tableRows = moverLevelRows_ + 4ull * std::max(1u, dynamicCount);
        if (moverGridTable_) device_.destroy(moverGridTable_);
        moverGridTable_ = makeBuffer("moverGridTable", tableRows * 16, rhi::BufferUsage::ShaderRead | rhi::BufferUsage::ShaderWrite);
        if (!moverGridData_ || !moverGridTable_) {
            fail(ErrorCode::DeviceFailure, "mover grids: the device could not create their buffers; movers are re-voxelized");
            moverGrids_.clear();
            for (auto& [id, inst] : instances_) inst.moverGrid = -1;
            return;
        }
        if (!rows.empty()) device_.writeBuffer(moverGridTable_, 0, rows.data(), rows.size() * sizeof(glm::uvec4));
        device_.beginMarker("build mover grids");
        device_.clearBuffer(moverGridData_, {0, words * 4}, 0xFFFFFFFFu);
        for (const MoverGrid& g : wanted)
            recordGather(meshes_.at(g.mesh), glm::mat4(1.0f), g.firstTriangle, 0, false, 0, moverGridData_, false);
        for (const MoverGrid& g : wanted) {
            struct { uint32_t triangleCount, firstTriangle, firstLevelRow, pad; } p{meshes_.at(g.mesh).triangleCount, g.firstTriangle,
                                                                                    g.firstLevelRow, 0};
            rhi::DispatchState s;
            s.shader = shaders_.buildMoverGrid;
            s.label = "sdf build mover grid";
            s.bindings.constants.push(rhi::constants(0, p));
            s.bindings.readBuffers.push({0, moverGridTable_, {}});
            s.bindings.storageBuffers.push({0, moverGridData_, {}, rhi::Access::Atomic});
            const uint64_t groups = (p.triangleCount + 63) / 64;
            const uint32_t gx = uint32_t(std::min<uint64_t>(groups, layout::kWideGroups));
            const uint32_t gy = uint32_t((groups + layout::kWideGroups - 1) / layout::kWideGroups);
            device_.dispatch(s, gx, gy, uint32_t(g.levels.size()));
        }
        device_.endMarker();
        report.moverGridsBuilt = uint32_t(wanted.size());
        moverGrids_ = std::move(wanted);
    }
    for (auto& [id, inst] : instances_) {
        if (!desc_.moverGrids || !inst.dynamic || inst.alphaTested) continue;
        const Mesh& mesh = meshes_.at(inst.mesh.id);
        if (!mesh.owned) continue;
        const float scale = gridScale(inst.transform);
        if (scale != 0.0f) inst.moverGrid = find(inst.mesh.id, scale);
    }
}

// The chunks of voxels a mover's references cover: per cascade it reaches, its footprint (as the overlay's
// jobs are made) within the cascade's window, in pieces of at most 4³ voxels. Counts them; appends them to
// `out` if given, as the triangle scratch holds them.
uint32_t SdfSceneImpl::moverChunks(const Instance& inst, float tag, uint32_t materialTag, std::vector<glm::vec4>* out) const {
    uint32_t count = 0;
    const int n = layout::kMoverChunkVoxels;
    for (uint32_t c = 0; c <= std::min(inst.maxCascade, desc_.cascadeCount - 1); ++c) {
        const float vs = voxelSize(c), b = band(c);
        const glm::ivec3 window = cascades_[c].origin;
        const glm::ivec3 lo = glm::max(glm::ivec3(glm::ceil((inst.bounds.min - b) / vs)) - 1, window);
        const glm::ivec3 hi = glm::min(glm::ivec3(glm::floor((inst.bounds.max + b) / vs)) + 1, window + int(kCascadeResolution));
        if (glm::any(glm::greaterThanEqual(lo, hi))) continue;
        for (int z = lo.z; z < hi.z; z += n)
            for (int y = lo.y; y < hi.y; y += n)
                for (int x = lo.x; x < hi.x; x += n) {
                    ++count;
                    if (!out) continue;
                    const glm::ivec3 last = glm::min(glm::ivec3(x, y, z) + n, hi) - 1;
                    out->push_back(glm::vec4(float(x), float(y), float(z), float(c)));
                    out->push_back(glm::vec4(glm::vec3(last), tag));
                    out->push_back(glm::vec4(0.0f, 0.0f, 0.0f, float(materialTag)));
                }
    }
    return count;
}

void SdfSceneImpl::writeMovers(const Round& round, std::vector<glm::vec4>& chunks) {
    std::vector<glm::uvec4> rows;
    uint32_t materialTag = 0;
    for (uint32_t id : round.instances) {
        const Instance& inst = instances_.at(id);
        const uint32_t tag = inst.material ? ++materialTag : 0u;
        if (inst.moverGrid < 0) continue;
        const MoverGrid& g = moverGrids_[size_t(inst.moverGrid)];
        const uint32_t mover = uint32_t(rows.size() / 4);
        const glm::mat4 toObject = glm::inverse(inst.transform);
        for (int r = 0; r < 3; ++r)
            rows.push_back(glm::uvec4(std::bit_cast<uint32_t>(toObject[0][r]), std::bit_cast<uint32_t>(toObject[1][r]),
                                      std::bit_cast<uint32_t>(toObject[2][r]), std::bit_cast<uint32_t>(toObject[3][r])));
        rows.push_back(glm::uvec4(std::bit_cast<uint32_t>(uniformScale(inst.transform)), tag, g.firstTriangle, g.firstLevelRow));
        moverChunks(inst, layout::kMoverTag + float(moverLevelRows_ / 4 + mover), tag, &chunks);
    }
    if (rows.empty()) return;
    const rhi::BufferDesc* table = device_.describe(moverGridTable_);
    const uint64_t bytes = (uint64_t(moverLevelRows_) + rows.size()) * 16;
    if (!table || table->size < bytes) {
        // More movers than when the grids were laid out: a larger table, levels first.
        device_.destroy(moverGridTable_);
        moverGridTable_ = makeBuffer("moverGridTable", bytes * 2, rhi::BufferUsage::ShaderRead | rhi::BufferUsage::ShaderWrite);
        if (!moverLevelTable_.empty()) device_.writeBuffer(moverGridTable_, 0, moverLevelTable_.data(), moverLevelTable_.size() * 16);
    }
    device_.writeBuffer(moverGridTable_, uint64_t(moverLevelRows_) * 16, rows.data(), rows.size() * sizeof(glm::uvec4));
}

}  // namespace bricklight::sdf::detail
