// Meshes and instances: validation (every error names the object and changes nothing), world bounds, and
// the dirty regions that adding, moving and removing static instances leave for the next update.
#include <cmath>

#include "../common/finite_checks.h"
#include "sdf_scene_impl.h"

namespace bricklight::sdf::detail {

namespace {
using bricklight::detail::finite;  // core/common/finite_checks.h
std::string quoted(const std::string& name) { return name.empty() ? std::string("(unnamed)") : "'" + name + "'"; }
}  // namespace

bool SdfSceneImpl::checkTransform(const glm::mat4& m, const std::string& what) {
    if (!finite(m)) return fail(ErrorCode::InvalidArgument, what + ": transform has a non-finite element");
    if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f)
        return fail(ErrorCode::InvalidArgument, what + ": transform is not affine (its last row must be 0, 0, 0, 1)");
    return true;
}

WorldBox SdfSceneImpl::worldBounds(const Mesh& mesh, const glm::mat4& t) const {
    WorldBox box{glm::vec3(INFINITY), glm::vec3(-INFINITY)};
    for (int i = 0; i < 8; ++i) {
        glm::vec3 corner((i & 1) ? mesh.boundsMax.x : mesh.boundsMin.x, (i & 2) ? mesh.boundsMax.y : mesh.boundsMin.y,
                         (i & 4) ? mesh.boundsMax.z : mesh.boundsMin.z);
        glm::vec3 w = glm::vec3(t * glm::vec4(corner, 1.0f));
        box.min = glm::min(box.min, w);
        box.max = glm::max(box.max, w);
    }
    return box;
}

void SdfSceneImpl::markDirty(const WorldBox& box, uint32_t maxCascade) {
    dirtyBoxes_.push_back(box);
    dirtyMaxCascade_.push_back(maxCascade);
}

MeshHandle SdfSceneImpl::createMesh(const MeshArrays& in) {
    const std::string what = "createMesh " + quoted(in.name);
    if (!in.positions || !in.vertexCount) return fail(ErrorCode::InvalidGeometry, what + ": no vertices"), MeshHandle{};
    if (!in.indices || !in.indexCount) return fail(ErrorCode::InvalidGeometry, what + ": no triangles (empty mesh)"), MeshHandle{};
    if (in.indexCount % 3) return fail(ErrorCode::InvalidGeometry, what + ": indexCount " + std::to_string(in.indexCount) + " is not a multiple of 3"), MeshHandle{};
    Mesh m;
    m.name = in.name;
    m.boundsMin = glm::vec3(INFINITY);
    m.boundsMax = glm::vec3(-INFINITY);
    for (uint32_t v = 0; v < in.vertexCount; ++v) {
        glm::vec3 p(in.positions[3 * v], in.positions[3 * v + 1], in.positions[3 * v + 2]);
        if (!finite(p)) return fail(ErrorCode::InvalidGeometry, what + ": vertex " + std::to_string(v) + " has a non-finite position"), MeshHandle{};
        m.boundsMin = glm::min(m.boundsMin, p);
        m.boundsMax = glm::max(m.boundsMax, p);
    }
    for (uint32_t i = 0; i < in.indexCount; ++i)
        if (in.indices[i] >= in.vertexCount)
            return fail(ErrorCode::InvalidGeometry, what + ": index " + std::to_string(i) + " (= " + std::to_string(in.indices[i]) +
                        ") is out of range (" + std::to_string(in.vertexCount) + " vertices)"),
                   MeshHandle{};
    m.owned = true;
    m.vertexCount = in.vertexCount;
    m.triangleCount = in.indexCount / 3;
    m.vertexBuffer = makeBuffer(("mesh " + in.name + " positions").c_str(), uint64_t(in.vertexCount) * 12,
                                rhi::BufferUsage::ShaderRead, in.positions);
    m.indexBuffer = makeBuffer(("mesh " + in.name + " indices").c_str(), uint64_t(in.indexCount) * 4,
                               rhi::BufferUsage::ShaderRead, in.indices);
    if (!m.vertexBuffer || !m.indexBuffer) {
        if (m.vertexBuffer) device_.destroy(m.vertexBuffer);
        if (m.indexBuffer) device_.destroy(m.indexBuffer);
        return fail(ErrorCode::DeviceFailure, what + ": the device could not create its buffers"), MeshHandle{};
    }
    const uint32_t id = nextMesh_++;
    meshes_[id] = std::move(m);
    return MeshHandle{id};
}

MeshHandle SdfSceneImpl::createMesh(const MeshBuffers& in) {
    const std::string what = "createMesh " + quoted(in.name);
    const rhi::BufferDesc* vb = device_.describe(in.vertexBuffer);
    const rhi::BufferDesc* ib = device_.describe(in.indexBuffer);
    if (!vb) return fail(ErrorCode::InvalidHandle, what + ": vertexBuffer is not a live buffer of this device"), MeshHandle{};
    if (!ib) return fail(ErrorCode::InvalidHandle, what + ": indexBuffer is not a live buffer of this device"), MeshHandle{};
    if (!(vb->usage & rhi::BufferUsage::ShaderRead)) return fail(ErrorCode::WrongFormat, what + ": vertexBuffer lacks BufferUsage::ShaderRead"), MeshHandle{};
    if (!(ib->usage & rhi::BufferUsage::ShaderRead)) return fail(ErrorCode::WrongFormat, what + ": indexBuffer lacks BufferUsage::ShaderRead"), MeshHandle{};
    if (!in.vertexCount || !in.triangleCount) return fail(ErrorCode::InvalidGeometry, what + ": no vertices or no triangles (empty mesh)"), MeshHandle{};
    const uint32_t positionBytes = in.positionFormat == PositionFormat::Float3 ? 12 : 8;
    if (in.vertexStride < positionBytes || in.vertexStride % 4 || in.vertexOffset % 4)
        return fail(ErrorCode::InvalidArgument, what + ": vertexStride " + std::to_string(in.vertexStride) + " / vertexOffset " +
                    std::to_string(in.vertexOffset) + " must be multiples of 4 and the stride at least " +
                    std::to_string(positionBytes) + " bytes"),
               MeshHandle{};
    const uint64_t vertexEnd = in.vertexOffset + uint64_t(in.vertexCount - 1) * in.vertexStride + positionBytes;
    if (vertexEnd > vb->size)
        return fail(ErrorCode::InvalidArgument, what + ": " + std::to_string(in.vertexCount) + " vertices end at byte " + std::to_string(vertexEnd) +
                    ", beyond the vertex buffer (" + std::to_string(vb->size) + " bytes)"),
               MeshHandle{};
    const uint32_t indexBytes = in.indexFormat == rhi::IndexFormat::U16 ? 2 : 4;
    if (in.indexOffset % indexBytes)
        return fail(ErrorCode::InvalidArgument, what + ": indexOffset " + std::to_string(in.indexOffset) + " is not a multiple of " +
                    std::to_string(indexBytes)),
               MeshHandle{};
    const uint64_t indexEnd = in.indexOffset + uint64_t(in.triangleCount) * 3 * indexBytes;
    // 16-bit indices are read as 32-bit words: the word holding the last index must lie in the buffer.
    if (((indexEnd + 3) & ~3ull) > ib->size)
        return fail(ErrorCode::InvalidArgument, what + ": " + std::to_string(in.triangleCount) + " triangles of indices end at byte " +
                    std::to_string(indexEnd) + ", beyond the index buffer (" + std::to_string(ib->size) + " bytes)"),
               MeshHandle{};
    if (!finite(in.boundsMin) || !finite(in.boundsMax) || glm::any(glm::greaterThan(in.boundsMin, in.boundsMax)))
        return fail(ErrorCode::InvalidArgument, what + ": bounds must be finite with min <= max"), MeshHandle{};
    Mesh m;
    m.name = in.name;
    m.vertexBuffer = in.vertexBuffer;
    m.indexBuffer = in.indexBuffer;
    m.vertexOffset = in.vertexOffset;
    m.indexOffset = in.indexOffset;
    m.vertexStride = in.vertexStride;
    m.positionFormat = in.positionFormat;
    m.vertexCount = in.vertexCount;
    m.indexFormat = in.indexFormat;
    m.triangleCount = in.triangleCount;
    m.boundsMin = in.boundsMin;
    m.boundsMax = in.boundsMax;
    const uint32_t id = nextMesh_++;
    meshes_[id] = std::move(m);
    return MeshHandle{id};
}

bool SdfSceneImpl::destroyMesh(MeshHandle h) {
    auto it = meshes_.find(h.id);
    if (it == meshes_.end()) return fail(ErrorCode::InvalidHandle, "destroyMesh: " + std::to_string(h.id) + " is not a live mesh");
    if (it->second.users)
        return fail(ErrorCode::InUse, "destroyMesh " + quoted(it->second.name) + ": still used by " + std::to_string(it->second.users) +
                    " instance(s)");
    if (it->second.owned) {
        device_.destroy(it->second.vertexBuffer);
        device_.destroy(it->second.indexBuffer);
    }
    meshes_.erase(it);
    return true;
}

InstanceHandle SdfSceneImpl::addInstance(const InstanceDesc& in) {
    auto mesh = meshes_.find(in.mesh.id);
    if (mesh == meshes_.end()) return fail(ErrorCode::InvalidHandle, "addInstance: mesh " + std::to_string(in.mesh.id) + " is not a live mesh"), InstanceHandle{};
    const std::string what = "addInstance of mesh " + quoted(mesh->second.name);
    if (instances_.size() >= desc_.maxInstances)
        return fail(ErrorCode::OverBudget, what + ": the scene already holds maxInstances (" + std::to_string(desc_.maxInstances) + ") instances"),
               InstanceHandle{};
    if (!checkTransform(in.transform, what)) return {};
    if (in.material) {
        const SurfaceMaterial& m = *in.material;
        if (!finite(m.albedo) || glm::any(glm::lessThan(m.albedo, glm::vec3(0.0f))) || glm::any(glm::greaterThan(m.albedo, glm::vec3(1.0f))))
            return fail(ErrorCode::InvalidArgument, what + ": material albedo must be finite and in [0, 1]"), InstanceHandle{};
        if (!finite(m.emission) || glm::any(glm::lessThan(m.emission, glm::vec3(0.0f))))
            return fail(ErrorCode::InvalidArgument, what + ": material emission must be finite and >= 0"), InstanceHandle{};
    }
    Instance inst;
    inst.mesh = in.mesh;
    inst.transform = in.transform;
    inst.dynamic = in.dynamic;
    inst.maxCascade = std::min(in.maxCascade, desc_.cascadeCount - 1);
    inst.alphaTested = in.alphaTested;
    inst.material = in.material;
    inst.bounds = worldBounds(mesh->second, in.transform);
    if (!finite(inst.bounds.min) || !finite(inst.bounds.max)) return fail(ErrorCode::InvalidArgument, what + ": world bounds overflow"), InstanceHandle{};
    if (!inst.dynamic) markDirty(inst.bounds, inst.maxCascade);
    inst.builtBounds = inst.bounds;
    inst.built = !inst.dynamic;
    mesh->second.users++;
    const uint32_t id = nextInstance_++;
    instances_[id] = inst;
    return InstanceHandle{id};
}

bool SdfSceneImpl::setTransform(InstanceHandle h, const glm::mat4& transform) {
    auto it = instances_.find(h.id);
    if (it == instances_.end()) return fail(ErrorCode::InvalidHandle, "setTransform: " + std::to_string(h.id) + " is not a live instance");
    Instance& inst = it->second;
    const std::string what = "setTransform of instance " + std::to_string(h.id);
    if (!checkTransform(transform, what)) return false;
    WorldBox next = worldBounds(meshes_.at(inst.mesh.id), transform);
    if (!finite(next.min) || !finite(next.max)) return fail(ErrorCode::InvalidArgument, what + ": world bounds overflow");
    if (!inst.dynamic) {
        // The bricks of the old and the new bounds are rebuilt, nothing else.
        markDirty(inst.bounds, inst.maxCascade);
        markDirty(next, inst.maxCascade);
        inst.builtBounds = next;
    }
    inst.transform = transform;
    inst.bounds = next;
    return true;
}

bool SdfSceneImpl::removeInstance(InstanceHandle h) {
    auto it = instances_.find(h.id);
    if (it == instances_.end()) return fail(ErrorCode::InvalidHandle, "removeInstance: " + std::to_string(h.id) + " is not a live instance");
    const Instance& inst = it->second;
    if (inst.built) markDirty(inst.builtBounds, inst.maxCascade);
    meshes_.at(inst.mesh.id).users--;
    instances_.erase(it);
    return true;
}

}  // namespace bricklight::sdf::detail
