// vct::VoxelScene: registered meshes voxelized through Clipmap::voxelizationState with our vertex shader
// (shaders/vct/voxelize_mesh.vert), or in compute (bricklight/voxelize_compute.glsl) with the big triangles
// drawn, culled against the clip-map's rewrite regions.
#include "bricklight/vct_scene.h"

#include <algorithm>
#include <cmath>

#include "../common/core_shaders.h"
#include "../common/finite_checks.h"
#include "../common/memory_tally.h"

namespace bricklight::vct {

struct VoxelScene::Mesh {
    uint32_t id = 0;
    std::string name;
    rhi::BufferHandle positions, normals, indices;  // ours (CPU arrays) or the application's
    uint64_t positionsOffset = 0, normalsOffset = 0, indicesOffset = 0;
    uint32_t positionsStride = 12, normalsStride = 12;
    uint32_t indexCount = 0, vertexCount = 0;
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};
    bool owned = false;
    bool computeReadable = false;  // the compute voxelizer can bind its buffers as read buffers
    uint32_t users = 0;  // instances
};

struct VoxelScene::Instance {
    uint32_t id = 0;
    Mesh* mesh = nullptr;
    glm::mat4 transform{1.0f};
    VoxelMaterial material;
    glm::vec4 user0{0.0f}, user1{0.0f};
};

namespace {

bool usableTransform(const glm::mat4& m) {
    if (!bricklight::detail::finite(m) || m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f) return false;
    const float det = glm::determinant(glm::mat3(m));
    return std::isfinite(det) && std::fabs(det) > 1e-12f;
}

// The vertex shader's per-instance constants (VoxelInstance in shaders/vct/voxelize_mesh_body.glsl, std140).
struct InstanceConstants {
    glm::mat4 transform;
    glm::vec4 normalRows[3];
    glm::vec4 user0, user1;
};
static_assert(sizeof(InstanceConstants) == 144);

// The compute voxelizer's constants (BlVoxelMeshInstance in bricklight/voxelize_compute.glsl, std140).
struct ComputeConstants {
    InstanceConstants instance;
    glm::uvec4 positions;  // first word, stride in words, triangles of this dispatch, has normals
    glm::uvec4 normals;    // first word, stride in words, vertices, first triangle of this dispatch
    glm::uvec4 indices;    // first word, first word of the instance's drawn list, word of its count
    glm::vec4 split;       // the largest extent voxelized in compute (finest voxels)
};
static_assert(sizeof(ComputeConstants) == 208);

constexpr uint32_t kComputeGroupSize = 64;        // local_size_x of bricklight/voxelize_compute.glsl
constexpr uint32_t kMaxGroupsPerDispatch = 65535;  // Vulkan's and GL's guaranteed minimum
constexpr uint32_t kDrawArgsWords = 5;            // rhi::DrawIndexedArgs

InstanceConstants instanceConstants(const glm::mat4& transform, const glm::vec4& user0, const glm::vec4& user1) {
    InstanceConstants c;
    c.transform = transform;
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(transform)));
    for (int r = 0; r < 3; ++r) c.normalRows[r] = glm::vec4(normalMatrix[0][r], normalMatrix[1][r], normalMatrix[2][r], 0.0f);
    c.user0 = user0;
    c.user1 = user1;
    return c;
}

template <typename T>
auto findById(std::vector<std::unique_ptr<T>>& items, uint32_t id) {
    return std::find_if(items.begin(), items.end(), [&](const auto& item) { return item->id == id; });
}

bool overlaps(const WorldBox& a, const WorldBox& b) {
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y && a.min.z <= b.max.z &&
           b.min.z <= a.max.z;
}

}  // namespace

VoxelScene::VoxelScene(rhi::IDevice& device) : device_(device) {}

std::unique_ptr<VoxelScene> VoxelScene::create(rhi::IDevice& device, Error* error) {
    shaders::link_bricklight_vct();
    std::unique_ptr<VoxelScene> s(new VoxelScene(device));
    auto shader = [&](const char* name) {
        rhi::ShaderDesc sd;
        sd.blob = rhi::findShader(name);
        return sd.blob ? device.createShader(sd) : rhi::ShaderHandle{};
    };
    s->vertex_ = shader("vct/voxelize_mesh.vert");
    s->vertexFlat_ = shader("vct/voxelize_mesh_flat.vert");
    s->compute_ = shader("vct/voxelize_mesh.comp");
    if (!s->vertex_ || !s->vertexFlat_ || !s->compute_) {
        if (error) *error = {ErrorCode::DeviceFailure, "voxel scene: the device could not create the voxelization vertex and compute shaders"};
        return nullptr;
    }
    return s;
}

VoxelScene::~VoxelScene() {
    for (const auto& m : meshes_)
        if (m->owned)
            for (rhi::BufferHandle b : {m->positions, m->normals, m->indices})
                if (b) device_.destroy(b);
    for (rhi::ShaderHandle h : {vertex_, vertexFlat_, compute_})
        if (h) device_.destroy(h);
    if (drawn_) device_.destroy(drawn_);
}

VoxelMeshHandle VoxelScene::createMesh(const VoxelMeshArrays& a, Error* error) {
    auto fail = [&](const std::string& why, ErrorCode code = ErrorCode::InvalidArgument) {
        if (error) *error = {code, "voxel scene: mesh '" + a.name + "': " + why};
        return VoxelMeshHandle{};
    };
    if (!a.positions || a.vertexCount == 0) return fail("no positions");
    if (!a.indices || a.indexCount == 0 || a.indexCount % 3 != 0) return fail("the index count must be a positive multiple of 3");
    auto mesh = std::make_unique<Mesh>();
    mesh->boundsMin = glm::vec3(INFINITY);
    mesh->boundsMax = glm::vec3(-INFINITY);
    for (uint32_t v = 0; v < a.vertexCount; ++v) {
        const glm::vec3 p(a.positions[3 * v], a.positions[3 * v + 1], a.positions[3 * v + 2]);
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return fail("vertex " + std::to_string(v) + " is not finite");
        if (a.normals && !(std::isfinite(a.normals[3 * v]) && std::isfinite(a.normals[3 * v + 1]) && std::isfinite(a.normals[3 * v + 2])))
            return fail("the normal of vertex " + std::to_string(v) + " is not finite");
        mesh->boundsMin = glm::min(mesh->boundsMin, p);
        mesh->boundsMax = glm::max(mesh->boundsMax, p);
    }
    for (uint32_t i = 0; i < a.indexCount; ++i)
        if (a.indices[i] >= a.vertexCount)
            return fail("index " + std::to_string(i) + " is " + std::to_string(a.indices[i]) + ", not below the vertex count " +
                        std::to_string(a.vertexCount));
    auto buffer = [&](const void* data, uint64_t bytes, uint32_t usage, const char* what) {
        rhi::BufferDesc bd;
        bd.size = bytes;
        bd.usage = usage;
        bd.debugName = "voxel scene " + a.name + " " + what;
        return device_.createBuffer(bd, data);
    };
    // ShaderRead too: the compute voxelizer reads them.
    mesh->positions = buffer(a.positions, uint64_t(a.vertexCount) * 12, rhi::BufferUsage::Vertex | rhi::BufferUsage::ShaderRead, "positions");
    if (a.normals)
        mesh->normals = buffer(a.normals, uint64_t(a.vertexCount) * 12, rhi::BufferUsage::Vertex | rhi::BufferUsage::ShaderRead, "normals");
    mesh->indices = buffer(a.indices, uint64_t(a.indexCount) * 4, rhi::BufferUsage::Index | rhi::BufferUsage::ShaderRead, "indices");
    mesh->owned = true;
    mesh->computeReadable = true;
    mesh->vertexCount = a.vertexCount;
    if (!mesh->positions || !mesh->indices || (a.normals && !mesh->normals)) {
        for (rhi::BufferHandle b : {mesh->positions, mesh->normals, mesh->indices})
            if (b) device_.destroy(b);
        return fail("the device could not create its buffers", ErrorCode::DeviceFailure);
    }
    mesh->indexCount = a.indexCount;
    mesh->name = a.name;
    mesh->id = nextId_++;
    meshes_.push_back(std::move(mesh));
    return VoxelMeshHandle{meshes_.back()->id};
}

VoxelMeshHandle VoxelScene::createMesh(const VoxelMeshBuffers& b, Error* error) {
    auto fail = [&](const std::string& why, ErrorCode code = ErrorCode::InvalidArgument) {
        if (error) *error = {code, "voxel scene: mesh '" + b.name + "': " + why};
        return VoxelMeshHandle{};
    };
    if (b.vertexCount == 0) return fail("no vertices");
    if (b.indexCount == 0 || b.indexCount % 3 != 0) return fail("the index count must be a positive multiple of 3");
    // An empty string when `h` is a live buffer of `usage` holding `bytes` from a 4-aligned `offset`.
    auto check = [&](rhi::BufferHandle h, uint64_t offset, uint64_t bytes, uint32_t usage, const std::string& what) -> std::string {
        const rhi::BufferDesc* d = device_.describe(h);
        if (!d) return what + " is not a live buffer";
        if (!(d->usage & usage)) return what + " lacks the " + (usage == rhi::BufferUsage::Index ? "Index" : "Vertex") + " usage";
        if (offset % 4 != 0 || offset + bytes > d->size)
            return what + " needs " + std::to_string(offset + bytes) + " bytes from a 4-aligned offset; buffer '" + d->debugName + "' has " +
                   std::to_string(d->size);
        return {};
    };
    if (b.positionsStride < 12 || (b.normals && b.normalsStride < 12)) return fail("a vertex stride is below 12 bytes");
    std::string why = check(b.positions, b.positionsOffset, uint64_t(b.positionsStride) * (b.vertexCount - 1) + 12, rhi::BufferUsage::Vertex,
                            "positions");
    if (why.empty() && b.normals)
        why = check(b.normals, b.normalsOffset, uint64_t(b.normalsStride) * (b.vertexCount - 1) + 12, rhi::BufferUsage::Vertex, "normals");
    if (why.empty()) why = check(b.indices, b.indicesOffset, uint64_t(b.indexCount) * 4, rhi::BufferUsage::Index, "indices");
    if (!why.empty()) return fail(why);
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(b.boundsMin[c]) || !std::isfinite(b.boundsMax[c]) || b.boundsMin[c] > b.boundsMax[c])
            return fail("the bounds must be finite with min <= max");
    auto mesh = std::make_unique<Mesh>();
    mesh->positions = b.positions;
    mesh->normals = b.normals;
    mesh->indices = b.indices;
    mesh->positionsOffset = b.positionsOffset;
    mesh->normalsOffset = b.normalsOffset;
    mesh->indicesOffset = b.indicesOffset;
    mesh->positionsStride = b.positionsStride;
    mesh->normalsStride = b.normalsStride;
    mesh->indexCount = b.indexCount;
    mesh->vertexCount = b.vertexCount;
    mesh->boundsMin = b.boundsMin;
    mesh->boundsMax = b.boundsMax;
    mesh->name = b.name;
    mesh->computeReadable = computeReadable(*mesh);
    mesh->id = nextId_++;
    meshes_.push_back(std::move(mesh));
    return VoxelMeshHandle{meshes_.back()->id};
}

bool VoxelScene::destroyMesh(VoxelMeshHandle handle, Error* error) {
    auto it = findById(meshes_, handle.id);
    if (it == meshes_.end()) {
        if (error) *error = {ErrorCode::InvalidHandle, "voxel scene: destroyMesh: unknown mesh " + std::to_string(handle.id)};
        return false;
    }
    if ((*it)->users) {
        if (error) *error = {ErrorCode::InUse, "voxel scene: mesh '" + (*it)->name + "' is used by " + std::to_string((*it)->users) + " instance(s)"};
        return false;
    }
    if ((*it)->owned)
        for (rhi::BufferHandle b : {(*it)->positions, (*it)->normals, (*it)->indices})
            if (b) device_.destroy(b);
    meshes_.erase(it);
    return true;
}

// The compute voxelizer binds the buffers whole as read buffers of words.
bool VoxelScene::computeReadable(const Mesh& mesh) const {
    for (rhi::BufferHandle h : {mesh.positions, mesh.normals, mesh.indices}) {
        if (!h) continue;
        const rhi::BufferDesc* d = device_.describe(h);
        if (!d || !(d->usage & rhi::BufferUsage::ShaderRead) || d->structStride != 0) return false;
    }
    return mesh.positionsStride % 4 == 0 && (!mesh.normals || mesh.normalsStride % 4 == 0) && mesh.positionsOffset % 4 == 0 &&
           mesh.normalsOffset % 4 == 0 && mesh.indicesOffset % 4 == 0;
}

WorldBox VoxelScene::worldBounds(const Mesh& mesh, const glm::mat4& t) const {
    WorldBox box{glm::vec3(INFINITY), glm::vec3(-INFINITY)};
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 corner((c & 1) ? mesh.boundsMax.x : mesh.boundsMin.x, (c & 2) ? mesh.boundsMax.y : mesh.boundsMin.y,
                               (c & 4) ? mesh.boundsMax.z : mesh.boundsMin.z);
        const glm::vec3 w = glm::vec3(t * glm::vec4(corner, 1.0f));
        box.min = glm::min(box.min, w);
        box.max = glm::max(box.max, w);
    }
    return box;
}

VoxelInstanceHandle VoxelScene::addInstance(const VoxelInstanceDesc& d, Error* error) {
    auto it = findById(meshes_, d.mesh.id);
    if (it == meshes_.end()) {
        if (error) *error = {ErrorCode::InvalidHandle, "voxel scene: addInstance: unknown mesh " + std::to_string(d.mesh.id)};
        return {};
    }
    const std::string who = "voxel scene: instance of mesh '" + (*it)->name + "': ";
    if (!usableTransform(d.transform)) {
        if (error) *error = {ErrorCode::InvalidArgument, who + "the transform must be finite, affine and invertible"};
        return {};
    }
    Error why;
    if (!checkVoxelMaterial(d.material, &why)) {
        if (error) *error = {why.code, who + why.message};
        return {};
    }
    if (d.material.computeShader && !d.material.fragmentShader) {
        if (error)
            *error = {ErrorCode::MissingInput, who + "the material has a computeShader but no fragmentShader: the compute voxelizer draws the triangles too big "
                           "for one invocation with the fragmentShader, and Voxelizer::Draws uses only it"};
        return {};
    }
    for (int c = 0; c < 4; ++c)
        if (!std::isfinite(d.user0[c]) || !std::isfinite(d.user1[c])) {
            if (error) *error = {ErrorCode::InvalidArgument, who + "user0 and user1 must be finite"};
            return {};
        }
    auto instance = std::make_unique<Instance>();
    instance->id = nextId_++;
    instance->mesh = it->get();
    instance->transform = d.transform;
    instance->material = d.material;
    instance->user0 = d.user0;
    instance->user1 = d.user1;
    ++instance->mesh->users;
    dirty_.push_back(worldBounds(*instance->mesh, d.transform));
    instances_.push_back(std::move(instance));
    return VoxelInstanceHandle{instances_.back()->id};
}

bool VoxelScene::setTransform(VoxelInstanceHandle handle, const glm::mat4& transform, Error* error) {
    auto it = findById(instances_, handle.id);
    if (it == instances_.end()) {
        if (error) *error = {ErrorCode::InvalidHandle, "voxel scene: setTransform: unknown instance " + std::to_string(handle.id)};
        return false;
    }
    if (!usableTransform(transform)) {
        if (error) *error = {ErrorCode::InvalidArgument, "voxel scene: instance of mesh '" + (*it)->mesh->name + "': the transform must be finite, affine and invertible"};
        return false;
    }
    dirty_.push_back(worldBounds(*(*it)->mesh, (*it)->transform));
    (*it)->transform = transform;
    dirty_.push_back(worldBounds(*(*it)->mesh, transform));
    return true;
}

bool VoxelScene::removeInstance(VoxelInstanceHandle handle, Error* error) {
    auto it = findById(instances_, handle.id);
    if (it == instances_.end()) {
        if (error) *error = {ErrorCode::InvalidHandle, "voxel scene: removeInstance: unknown instance " + std::to_string(handle.id)};
        return false;
    }
    dirty_.push_back(worldBounds(*(*it)->mesh, (*it)->transform));
    --(*it)->mesh->users;
    instances_.erase(it);
    return true;
}

std::vector<WorldBox> VoxelScene::takeDirtyRegions() {
    std::vector<WorldBox> out;
    out.swap(dirty_);
    return out;
}

void VoxelScene::setVoxelizer(Voxelizer voxelizer, const ComputeVoxelizer& options) {
    voxelizer_ = voxelizer;
    computeOptions_ = options;
    if (!(computeOptions_.splitVoxels >= 0.0f)) computeOptions_.splitVoxels = 0.0f;  // NaN: draw every triangle
}

bool VoxelScene::voxelize(Clipmap& clipmap, const rhi::Bindings& extra, Error* error) {
    lastDraws_ = 0;
    lastComputes_ = 0;
    const std::vector<WorldBox> regions = clipmap.dirtyRegions();
    const float margin = clipmap.placement().voxelSize(clipmap.desc().levels - 1);
    bool ok = true;
    auto refuse = [&](const Mesh& mesh, const std::string& why, ErrorCode code = ErrorCode::InvalidArgument) {
        if (error && ok) *error = {code, "voxel scene: instance of mesh '" + mesh.name + "': " + why};
        ok = false;
    };
    // What this call writes, instance by instance; the constants live here until the calls that point at them.
    struct Work {
        const Instance* instance = nullptr;
        rhi::DrawCallState state;
        bool compute = false;
        uint64_t argsWord = 0, listWord = 0;  // compute: its draw's arguments and its drawn-triangle list
        InstanceConstants constants;
        ComputeConstants computeConstants;
    };
    std::vector<Work> work;
    work.reserve(instances_.size());
    uint32_t computeCount = 0;
    for (const auto& instance : instances_) {
        const Mesh& mesh = *instance->mesh;
        // Grown by the coarsest level's voxel: the geometry stage dilates each level's triangles by half a voxel.
        WorldBox bounds = worldBounds(mesh, instance->transform);
        bounds.min -= glm::vec3(margin);
        bounds.max += glm::vec3(margin);
        if (std::none_of(regions.begin(), regions.end(), [&](const WorldBox& r) { return overlaps(bounds, r); })) continue;
        Error why;
        std::optional<rhi::DrawCallState> state = clipmap.voxelizationState(instance->material, &why);
        if (!state) {
            refuse(mesh, why.message, why.code);
            continue;
        }
        Work& w = work.emplace_back();
        w.instance = instance.get();
        w.state = *state;
        w.state.label = "vct voxelize registered mesh";
        w.state.vertexShader = mesh.normals ? vertex_ : vertexFlat_;
        w.state.vertexInputs.push({0, rhi::VertexFormat::Float3, 0, 0});
        w.state.vertexBuffers.push({mesh.positions, mesh.positionsOffset, mesh.positionsStride, false});
        if (mesh.normals) {
            w.state.vertexInputs.push({1, rhi::VertexFormat::Float3, 1, 0});
            w.state.vertexBuffers.push({mesh.normals, mesh.normalsOffset, mesh.normalsStride, false});
        }
        w.state.indexBuffer = {mesh.indices, mesh.indicesOffset, rhi::IndexFormat::U32};
        w.constants = instanceConstants(instance->transform, instance->user0, instance->user1);
        // A material with its own fragment shader needs its own compute shader, or its emittance would be lost.
        const VoxelMaterial& m = instance->material;
        w.compute = voxelizer_ == Voxelizer::Compute && mesh.computeReadable && (m.computeShader || !m.fragmentShader);
        if (w.compute) ++computeCount;
    }

    // The compute instances' drawn-triangle lists: DrawIndexedArgs for each, then room for all its indices.
    std::vector<uint32_t> args;
    if (computeCount) {
        uint64_t words = uint64_t(computeCount) * kDrawArgsWords;
        for (Work& w : work) {
            if (!w.compute) continue;
            w.argsWord = args.size();
            w.listWord = words;
            words += w.instance->mesh->indexCount;
            args.insert(args.end(), {0u, 1u, uint32_t(w.listWord), 0u, 0u});
        }
        if (words > UINT32_MAX) {
            refuse(*work.front().instance->mesh, "the compute voxelizer's drawn-triangle lists exceed 2^32 indices; instances are drawn", ErrorCode::OverBudget);
            for (Work& w : work) w.compute = false;
            computeCount = 0;
        } else if (words * 4 > drawnBytes_) {
            if (drawn_) device_.destroy(drawn_);
            rhi::BufferDesc bd;
            bd.size = std::max<uint64_t>((words + words / 2) * 4, 4096);  // room to grow: half as much again
            bd.usage = rhi::BufferUsage::ShaderWrite | rhi::BufferUsage::Index | rhi::BufferUsage::IndirectArgs;
            bd.debugName = "voxel scene drawn triangles";
            drawn_ = device_.createBuffer(bd);
            drawnBytes_ = drawn_ ? bd.size : 0;
            if (!drawn_) {
                refuse(*work.front().instance->mesh, "the device could not create the compute voxelizer's list buffer; instances are drawn", ErrorCode::DeviceFailure);
                for (Work& w : work) w.compute = false;
                computeCount = 0;
            }
        }
        if (computeCount) device_.writeBuffer(drawn_, 0, args.data(), args.size() * 4);
    }

    // The dispatches first, one after another: they accumulate with atomics as the draws do, so only the first
    // needs a barrier after the update's clears.
    bool previousWasDispatch = false;
    for (Work& w : work) {
        if (!w.compute) continue;
        const Mesh& mesh = *w.instance->mesh;
        rhi::DispatchState ds;
        ds.shader = w.instance->material.computeShader ? w.instance->material.computeShader : compute_;
        ds.label = "vct voxelize registered mesh (compute)";
        ds.bindings = w.state.bindings;  // the clip-map's: material constants, frame, emittance, counters, opacity
        ComputeConstants& c = w.computeConstants;
        c.instance = w.constants;
        c.positions = glm::uvec4(uint32_t(mesh.positionsOffset / 4), mesh.positionsStride / 4, 0u, mesh.normals ? 1u : 0u);
        c.normals = glm::uvec4(uint32_t(mesh.normalsOffset / 4), mesh.normalsStride / 4, mesh.vertexCount, 0u);
        c.indices = glm::uvec4(uint32_t(mesh.indicesOffset / 4), uint32_t(w.listWord), uint32_t(w.argsWord), 0u);
        c.split = glm::vec4(computeOptions_.splitVoxels, 0.0f, 0.0f, 0.0f);
        ds.bindings.constants.push(rhi::constants(kVoxelSceneInstanceConstants, c));
        auto read = [&](uint8_t slot, rhi::BufferHandle buffer) {
            rhi::ReadBufferBinding b;
            b.slot = slot;
            b.buffer = buffer;
            ds.bindings.readBuffers.push(b);
        };
        read(4, mesh.positions);
        read(5, mesh.normals ? mesh.normals : mesh.positions);
        read(6, mesh.indices);
        rhi::StorageBufferBinding list;
        list.slot = 5;
        list.buffer = drawn_;
        list.access = rhi::Access::ReadWrite;
        ds.bindings.storageBuffers.push(list);
        // `extra` is the emittance functions' own resources: ours (opacity only) declare none.
        if (w.instance->material.computeShader) rhi::appendBindings(ds.bindings, extra);
        const uint32_t triangles = mesh.indexCount / 3;
        const uint32_t perDispatch = kMaxGroupsPerDispatch * kComputeGroupSize;
        for (uint32_t first = 0; first < triangles; first += perDispatch) {
            c.positions.z = std::min(perDispatch, triangles - first);
            c.normals.w = first;
            ds.flags = previousWasDispatch ? rhi::DispatchFlags::NoBarrierWithPreviousWriter : 0u;
            // One invocation per triangle and level (groups in y: the levels).
            if (!device_.dispatch(ds, (c.positions.z + kComputeGroupSize - 1) / kComputeGroupSize, clipmap.desc().levels, 1)) {
                refuse(mesh, "the device refused the compute voxelizer's dispatch (is the material's computeShader a compute shader "
                             "that includes bricklight/voxelize_compute.glsl, and do `extra`'s bindings leave its slots free?)" +
                                 std::string(first == 0 ? "; the instance is drawn instead" : ""), ErrorCode::DeviceFailure);
                // A refused call writes nothing: refused from the start, the draw path takes the whole instance.
                if (first == 0) w.compute = false;
                break;
            }
            previousWasDispatch = true;
        }
        if (w.compute) ++lastComputes_;
    }

    for (Work& w : work) {
        w.state.bindings.constants.push(rhi::constants(kVoxelSceneInstanceConstants, w.constants));
        if (w.instance->material.fragmentShader) rhi::appendBindings(w.state.bindings, extra);
        if (w.compute) {
            // The triangles the dispatch left to the draw path (the arguments' index count is what it appended).
            w.state.indexBuffer = {drawn_, 0, rhi::IndexFormat::U32};
            device_.drawIndirect(w.state, drawn_, w.argsWord * 4, true);
        } else {
            rhi::DrawIndexedArgs a;
            a.indexCount = w.instance->mesh->indexCount;
            device_.drawIndexed(w.state, a);
        }
        ++lastDraws_;
    }
    return ok;
}

MemoryUse VoxelScene::memoryUse() const {
    bricklight::detail::MemoryTally tally(device_);
    for (const auto& mesh : meshes_)
        if (mesh->owned) tally.add(mesh->positions).add(mesh->normals).add(mesh->indices);
    tally.add(drawn_);
    return tally.use();
}

}  // namespace bricklight::vct
