// SdfScene creation: description checks, device capability checks, the persistent resources and the
// per-update scratch; memory accounting; the CPU snapshot of the field.
#include <cmath>
#include <cstdio>
#include <numeric>

#include "../common/core_shaders.h"
#include "sdf_scene_impl.h"

namespace bricklight::sdf {

float suggestVoxelSize(float extent, uint32_t cascadeCount) {
    if (!(extent > 0.0f) || cascadeCount == 0) return 0.0f;
    const uint32_t n = std::min(cascadeCount, kMaxCascades);
    // The coarsest cascade spans 64 voxels of finest * 2^(n-1); keep half of it on each side of the centre.
    return 2.0f * extent / (float(kCascadeResolution) * float(1u << (n - 1)));
}

std::unique_ptr<SdfScene> SdfScene::create(rhi::IDevice& device, const SceneDesc& desc, Error* error) {
    auto scene = std::make_unique<detail::SdfSceneImpl>(device, desc);
    if (!scene->init(error)) return nullptr;
    return scene;
}

uint32_t FieldSnapshot::voxelState(uint32_t cascade, glm::ivec3 logical) const {
    const Cascade& c = cascades.at(cascade);
    glm::ivec3 world = c.origin + logical;
    glm::ivec3 p = world & glm::ivec3(int(kCascadeResolution) - 1);
    return c.brickMap[size_t((p.z * 64 + p.y) * 64 + p.x)];
}

uint8_t FieldSnapshot::brixel(uint32_t brick, glm::ivec3 b) const {
    const uint32_t n = atlasBricksPerAxis, side = n * kBrickResolution;
    glm::uvec3 base(brick % n, (brick / n) % n, brick / (n * n));
    glm::uvec3 t = base * kBrickResolution + glm::uvec3(b);
    return atlas[(size_t(t.z) * side + t.y) * side + t.x];
}

float FieldSnapshot::sampleDistance(uint32_t cascade, glm::ivec3 logical, glm::ivec3 b) const {
    const uint32_t state = voxelState(cascade, logical);
    const float band = kDistanceBandBrixels / 7.0f * cascades[cascade].voxelSize;
    if (state == kEmpty) return band;
    if (state >= layout::kFirstState) return -1.0f;
    return float(brixel(state, b)) / 255.0f * band;
}

namespace detail {

SdfSceneImpl::~SdfSceneImpl() {
    for (auto& [id, m] : meshes_)
        if (m.owned) {
            device_.destroy(m.vertexBuffer);
            device_.destroy(m.indexBuffer);
        }
    for (rhi::BufferHandle b : {cascadeTable_, brickMaps_, baseMaps_, splitBricks_, splitWork_, splitMinima_, splitMaterials_, trees_, brickAabbs_, brickOwners_, freeStack_, counters_, args_,
                                voxelRefs_, triangles_, references_, sortedReferences_, touched_, jobTable_, materialTable_, overlays_,
                                moverGridData_, moverGridTable_})
        if (b) device_.destroy(b);
    if (atlas_) device_.destroy(atlas_);
    if (atlasSampler_) device_.destroy(atlasSampler_);
    for (rhi::ShaderHandle s : {shaders_.invalidate, shaders_.gather, shaders_.count, shaders_.prepare, shaders_.allocate,
                                shaders_.scatter, shaders_.emit, shaders_.finalizeSplit, shaders_.resolve, shaders_.prepareOverlay, shaders_.resolveOverlay,
                                shaders_.treeBottom, shaders_.treeTop, shaders_.debug, shaders_.buildMoverGrid})
        if (s) device_.destroy(s);
}

bool SdfSceneImpl::fail(ErrorCode code, const std::string& message) {
    log_.report(desc_.errorCallback, rhi::Severity::Error, code, message);
    return false;
}

float SdfSceneImpl::voxelSize(uint32_t cascade) const { return desc_.finestVoxelSize * float(1u << cascade); }
float SdfSceneImpl::band(uint32_t cascade) const { return kDistanceBandBrixels / 7.0f * voxelSize(cascade); }
uint32_t SdfSceneImpl::brickCapacity() const {
    const uint32_t n = desc_.atlasBricksPerAxis;
    return n * n * n;
}
glm::ivec3 SdfSceneImpl::cascadeOrigin(uint32_t cascade) const {
    return cascade < cascades_.size() ? cascades_[cascade].origin : glm::ivec3(0);
}
float SdfSceneImpl::cascadeVoxelSize(uint32_t cascade) const { return cascade < cascades_.size() ? voxelSize(cascade) : 0.0f; }

rhi::BufferHandle SdfSceneImpl::makeBuffer(const char* name, uint64_t size, uint32_t usage, const void* data) {
    rhi::BufferDesc d;
    d.size = size;
    d.usage = usage;
    d.debugName = desc_.debugName + "." + name;
    return device_.createBuffer(d, data);
}

bool SdfSceneImpl::init(Error* error) {
    auto bad = [&](ErrorCode code, const std::string& m) {
        fail(code, m);
        if (error) *error = lastError();
        return false;
    };
    const SceneDesc& d = desc_;
    if (d.cascadeCount < 1 || d.cascadeCount > kMaxCascades)
        return bad(ErrorCode::InvalidArgument, "cascadeCount " + std::to_string(d.cascadeCount) + " is outside 1.." + std::to_string(kMaxCascades));
    if (!(d.finestVoxelSize > 0.0f) || !std::isfinite(d.finestVoxelSize))
        return bad(ErrorCode::InvalidArgument, "finestVoxelSize must be a positive finite number (got " + std::to_string(d.finestVoxelSize) + ")");
    if (!std::isfinite(d.finestVoxelSize * float(1u << (d.cascadeCount - 1)) * 64.0f * 1e3f))
        return bad(ErrorCode::InvalidArgument, "finestVoxelSize is too large for " + std::to_string(d.cascadeCount) + " cascades");
    if (d.atlasBricksPerAxis < 1 || d.atlasBricksPerAxis > 128)
        return bad(ErrorCode::InvalidArgument, "atlasBricksPerAxis " + std::to_string(d.atlasBricksPerAxis) + " is outside 1..128");
    const Budgets& b = d.budgets;
    if (!b.maxTrianglesPerUpdate || !b.maxReferencesPerUpdate || !b.maxVoxelsPerUpdate || !b.maxJobsPerUpdate)
        return bad(ErrorCode::InvalidArgument, "every budget must be at least 1");
    if (b.maxReferencesPerUpdate > (1u << 28) || b.maxTrianglesPerUpdate > (1u << 26))
        return bad(ErrorCode::InvalidArgument, "budgets too large (at most 2^28 references, 2^26 triangles per update)");
    if (d.maxInstances < 1) return bad(ErrorCode::InvalidArgument, "maxInstances must be at least 1");

    const rhi::Capabilities& caps = device_.capabilities();
    using FS = uint32_t;
    const FS atlasNeeds = rhi::FormatSupport::Sampled | rhi::FormatSupport::Filterable | rhi::FormatSupport::Storage;
    if (!caps.supports(rhi::Format::R8_UNORM, atlasNeeds))
        return bad(ErrorCode::Unsupported, "device '" + caps.deviceName + "' cannot sample, filter and store R8_UNORM (the brick atlas format)");
    const uint32_t atlasSide = d.atlasBricksPerAxis * kBrickResolution;
    if (caps.limits.maxTextureSize3D && atlasSide > caps.limits.maxTextureSize3D)
        return bad(ErrorCode::Unsupported, "atlas side " + std::to_string(atlasSide) + " exceeds the device's 3D texture limit " +
                   std::to_string(caps.limits.maxTextureSize3D));
    if (caps.limits.maxComputeGroupInvocations && caps.limits.maxComputeGroupInvocations < 512)
        return bad(ErrorCode::Unsupported, "the device allows fewer than 512 invocations per group (the brick pass needs 512)");

    // Every buffer is bound whole: each must fit the device's storage-buffer range.
    const uint64_t range = caps.limits.maxStorageBufferRange;
    auto fits = [&](const char* what, uint64_t bytes, const char* budget) {
        if (!range || bytes <= range) return true;
        return bad(ErrorCode::Unsupported, std::string(what) + " needs " + std::to_string(bytes) + " bytes, more than the device's maxStorageBufferRange (" +
                   std::to_string(range) + "): lower " + budget);
    };
    const uint64_t cascadeEntries = uint64_t(d.cascadeCount) * layout::kCascadeVoxels;
    if (!fits("the reference scratch", uint64_t(b.maxReferencesPerUpdate) * 12, "budgets.maxReferencesPerUpdate") ||
        !fits("the triangle scratch", uint64_t(b.maxTrianglesPerUpdate) * 48, "budgets.maxTrianglesPerUpdate") ||
        !fits("the voxel reference counts", cascadeEntries * 8, "cascadeCount") ||
        !fits("the touched-voxel list", std::min<uint64_t>(b.maxVoxelsPerUpdate, cascadeEntries) * 16, "budgets.maxVoxelsPerUpdate"))
        return false;

    shaders::link_bricklight_sdf();
    auto shader = [&](const char* name, rhi::ShaderHandle* out) {
        const rhi::ShaderBlob* blob = rhi::findShader(name);
        if (!blob) return bad(ErrorCode::Unsupported, std::string("shader '") + name + "' is not linked into this program");
        rhi::ShaderDesc sd;
        sd.blob = blob;
        *out = device_.createShader(sd);
        return *out ? true : bad(ErrorCode::DeviceFailure, std::string("the device could not create shader '") + name + "'");
    };
    if (!shader("sdf/invalidate_jobs.comp", &shaders_.invalidate) || !shader("sdf/gather_triangles.comp", &shaders_.gather) ||
        !shader("sdf/count_references.comp", &shaders_.count) || !shader("sdf/prepare_args.comp", &shaders_.prepare) ||
        !shader("sdf/allocate_bricks.comp", &shaders_.allocate) ||
        !shader("sdf/scatter_references.comp", &shaders_.scatter) || !shader("sdf/emit_distances.comp", &shaders_.emit) ||
        !shader("sdf/resolve_empty.comp", &shaders_.resolve) || !shader("sdf/prepare_overlay.comp", &shaders_.prepareOverlay) ||
        !shader("sdf/resolve_overlay.comp", &shaders_.resolveOverlay) ||
        !shader("sdf/finalize_split_bricks.comp", &shaders_.finalizeSplit) || !shader("sdf/build_tree_bottom.comp", &shaders_.treeBottom) ||
        !shader("sdf/build_tree_top.comp", &shaders_.treeTop) || !shader("sdf/debug_view.comp", &shaders_.debug) ||
        !shader("sdf/build_mover_grid.comp", &shaders_.buildMoverGrid))
        return false;

    using namespace rhi::BufferUsage;
    const uint32_t rw = ShaderRead | ShaderWrite;
    const uint32_t capacity = brickCapacity();
    const uint64_t mapEntries = uint64_t(d.cascadeCount) * layout::kCascadeVoxels;

    rhi::TextureDesc atlas;
    atlas.dimension = rhi::TextureDimension::Texture3D;
    atlas.format = rhi::Format::R8_UNORM;
    atlas.width = atlas.height = atlas.depthOrLayers = atlasSide;
    atlas.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::Storage;
    atlas.debugName = d.debugName + ".atlas";
    atlas_ = device_.createTexture(atlas);
    rhi::SamplerDesc sampler;
    sampler.minFilter = sampler.magFilter = rhi::Filter::Linear;
    sampler.mipFilter = rhi::Filter::Nearest;
    sampler.debugName = d.debugName + ".atlasSampler";
    atlasSampler_ = device_.createSampler(sampler);

    std::vector<uint32_t> unbuilt(mapEntries, layout::kUnbuilt);
    brickMaps_ = makeBuffer("brickMaps", mapEntries * 4, rw, unbuilt.data());
    std::vector<uint32_t> noBase(mapEntries, layout::kNoBase);
    baseMaps_ = makeBuffer("baseMaps", mapEntries * 4, rw, noBase.data());
    std::vector<uint32_t> emptyTrees(size_t(d.cascadeCount) * layout::kTreeStride, 0);
    trees_ = makeBuffer("trees", emptyTrees.size() * 4, rw, emptyTrees.data());
    // Boxes and opaque cells start as "none", materials as "unknown" (0).
    std::vector<uint32_t> brickInfo(size_t(capacity) * layout::kBrickInfoWords, 0u);
    std::fill(brickInfo.begin(), brickInfo.begin() + size_t(capacity) * (1 + layout::kOpaqueCellWords), layout::kAabbNone);
    brickAabbs_ = makeBuffer("brickAabbs", brickInfo.size() * 4, rw, brickInfo.data());
    static_assert(layout::kNoOwner == layout::kAabbNone, "one fill serves both");
    brickOwners_ = makeBuffer("brickOwners", uint64_t(capacity) * 4, rw, brickInfo.data());
    std::vector<uint32_t> stack(capacity);
    std::iota(stack.begin(), stack.end(), 0u);
    freeStack_ = makeBuffer("freeStack", uint64_t(capacity) * 4, rw, stack.data());
    std::vector<uint32_t> counters(layout::CounterCount, 0);
    counters[layout::FreeCount] = capacity;
    counters_ = makeBuffer("counters", counters.size() * 4, rw, counters.data());
    std::vector<uint32_t> zeroArgs(layout::kArgsBytes / 4, 0);
    args_ = makeBuffer("indirectArgs", layout::kArgsBytes, rw | IndirectArgs, zeroArgs.data());
    voxelRefs_ = makeBuffer("voxelReferenceCounts", mapEntries * 8, rw);
    cascadeTable_ = makeBuffer("cascadeTable", sizeof(layout::GpuCascadeTable), ShaderRead);

    touchedCapacity_ = uint32_t(std::min<uint64_t>(b.maxVoxelsPerUpdate, mapEntries));
    // A split brick has more than kRefsPerGroup references: its chunks number at most 2 per kRefsPerGroup.
    const uint64_t splitWork = 2ull * (b.maxReferencesPerUpdate / layout::kRefsPerGroup + 1);
    splitBricks_ = makeBuffer("splitBricks", uint64_t(layout::kMaxSplitBricks) * 16, rw);
    splitWork_ = makeBuffer("splitWork", splitWork * 8, rw);
    std::vector<uint32_t> clearMinima(size_t(layout::kMaxSplitBricks) * 1024, layout::kSplitMinimumClear);
    splitMinima_ = makeBuffer("splitMinima", clearMinima.size() * 4, rw, clearMinima.data());
    splitMaterials_ = makeBuffer("splitMaterials", splitWork * 32, rw);
    triangles_ = makeBuffer("triangles", uint64_t(b.maxTrianglesPerUpdate) * 48, rw);
    references_ = makeBuffer("references", uint64_t(b.maxReferencesPerUpdate) * 12, rw);
    sortedReferences_ = makeBuffer("sortedReferences", uint64_t(b.maxReferencesPerUpdate) * 4, rw);
    touched_ = makeBuffer("touchedVoxels", uint64_t(touchedCapacity_) * 16, rw);
    materialTable_ = makeBuffer("materialTable", uint64_t(std::max(1u, d.maxInstances)) * layout::kMaterialTableBytesPerInstance, ShaderRead);
    jobTable_ = makeBuffer("jobTable", (layout::kJobTableHeadInts + 4ull * b.maxJobsPerUpdate) * 16, ShaderRead);
    overlays_ = makeBuffer("debugOverlays", 32ull * std::max(1u, d.maxBoundsOverlays), ShaderRead);
    // Bound by the brick pass always; replaced when the first mover grid is built (sdf_mover_grids.cpp).
    moverGridData_ = makeBuffer("moverGridData", 16, rw);
    moverGridTable_ = makeBuffer("moverGridTable", 64, rw);

    for (rhi::BufferHandle h : {cascadeTable_, brickMaps_, baseMaps_, splitBricks_, splitWork_, splitMinima_, splitMaterials_, trees_, brickAabbs_, brickOwners_, freeStack_, counters_, args_,
                                voxelRefs_, triangles_, references_, sortedReferences_, touched_, jobTable_, materialTable_, overlays_,
                                moverGridData_, moverGridTable_})
        if (!h) return bad(ErrorCode::DeviceFailure, "the device could not create the field's buffers (see the device's messages)");
    if (!atlas_ || !atlasSampler_) return bad(ErrorCode::DeviceFailure, "the device could not create the brick atlas (see the device's messages)");

    cascades_.resize(d.cascadeCount);
    adaptiveVoxelLimit_ = b.maxVoxelsPerUpdate;
    stats_.bricksCapacity = stats_.bricksFree = capacity;
    writeCascadeTable();
    return true;
}

MemoryUse SdfSceneImpl::memoryUse() const {
    MemoryUse m;
    auto add = [&](const char* name, uint64_t bytes) {
        m.resources.push_back({name, bytes});
        m.totalBytes += bytes;
    };
    const uint64_t side = uint64_t(desc_.atlasBricksPerAxis) * kBrickResolution;
    add("atlas (R8_UNORM 3D)", side * side * side);
    for (auto [name, h] : std::initializer_list<std::pair<const char*, rhi::BufferHandle>>{
             {"brickMaps", brickMaps_}, {"baseMaps", baseMaps_}, {"trees", trees_}, {"split bricks (scratch)", splitBricks_},
             {"split chunks (scratch)", splitWork_}, {"split minima (scratch)", splitMinima_}, {"split materials (scratch)", splitMaterials_}, {"brickAabbs (boxes, cells, materials)", brickAabbs_}, {"brickOwners", brickOwners_},
             {"freeStack", freeStack_}, {"voxelReferenceCounts", voxelRefs_}, {"cascadeTable", cascadeTable_},
             {"counters+args", counters_}, {"triangles (scratch)", triangles_}, {"references (scratch)", references_},
             {"sortedReferences (scratch)", sortedReferences_}, {"touchedVoxels (scratch)", touched_},
             {"jobTable", jobTable_}, {"materialTable", materialTable_}, {"debugOverlays", overlays_},
             {"mover grids (triangles, nearest-triangle keys)", moverGridData_}, {"mover grid table", moverGridTable_}}) {
        const rhi::BufferDesc* bd = device_.describe(h);
        add(name, bd ? bd->size : 0);
    }
    for (const auto& [id, mesh] : meshes_)
        if (mesh.owned) {
            const rhi::BufferDesc* v = device_.describe(mesh.vertexBuffer);
            const rhi::BufferDesc* i = device_.describe(mesh.indexBuffer);
            m.totalBytes += (v ? v->size : 0) + (i ? i->size : 0);
            if (m.resources.empty() || m.resources.back().name != "meshes (from CPU arrays)")
                m.resources.push_back({"meshes (from CPU arrays)", 0});
            m.resources.back().bytes += (v ? v->size : 0) + (i ? i->size : 0);
        }
    return m;
}

FieldSnapshot SdfSceneImpl::readField() {
    FieldSnapshot s;
    s.atlasBricksPerAxis = desc_.atlasBricksPerAxis;
    const uint64_t side = uint64_t(desc_.atlasBricksPerAxis) * kBrickResolution;
    s.atlas.resize(side * side * side);
    device_.readTexture(atlas_, {}, s.atlas.data());
    s.brickAabbs.resize(brickCapacity());
    device_.readBuffer(brickAabbs_, 0, s.brickAabbs.size() * 4, s.brickAabbs.data());
    s.brickOpaqueCells.resize(size_t(brickCapacity()) * layout::kOpaqueCellWords);
    device_.readBuffer(brickAabbs_, uint64_t(brickCapacity()) * 4, s.brickOpaqueCells.size() * 4, s.brickOpaqueCells.data());
    s.brickMaterials.resize(size_t(brickCapacity()) * layout::kMaterialWords);
    device_.readBuffer(brickAabbs_, uint64_t(brickCapacity()) * 4 * (1 + layout::kOpaqueCellWords), s.brickMaterials.size() * 4,
                       s.brickMaterials.data());
    std::vector<uint32_t> maps(size_t(desc_.cascadeCount) * layout::kCascadeVoxels), bases(maps.size());
    device_.readBuffer(brickMaps_, 0, maps.size() * 4, maps.data());
    device_.readBuffer(baseMaps_, 0, bases.size() * 4, bases.data());
    for (uint32_t c = 0; c < desc_.cascadeCount; ++c) {
        FieldSnapshot::Cascade fc;
        fc.origin = cascades_[c].origin;
        fc.voxelSize = voxelSize(c);
        fc.brickMap.assign(maps.begin() + size_t(c) * layout::kCascadeVoxels,
                           maps.begin() + size_t(c + 1) * layout::kCascadeVoxels);
        fc.baseMap.assign(bases.begin() + size_t(c) * layout::kCascadeVoxels, bases.begin() + size_t(c + 1) * layout::kCascadeVoxels);
        s.cascades.push_back(std::move(fc));
    }
    pollStats();
    return s;
}

}  // namespace detail
}  // namespace bricklight::sdf
