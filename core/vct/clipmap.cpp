// vct::Clipmap: the clip-map's resources on a device, the clears and refills an update needs, and the draw
// records through which the application voxelizes its meshes.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "bricklight/vct.h"
#include "../common/core_shaders.h"
#include "../common/refusal.h"
#include "clipmap_regions.h"

namespace bricklight::vct {

bool checkVoxelMaterial(const VoxelMaterial& m, Error* error) {
    const bricklight::detail::Refusal fail(error, "voxel material");
    if (!(m.thickness >= 0.0f && m.thickness <= 2.0f))
        return fail("thickness " + std::to_string(m.thickness) + " is outside 0..2 voxels");
    if (!(m.opacity >= 0.0f && m.opacity <= 1.0f)) return fail("opacity " + std::to_string(m.opacity) + " is outside 0..1");
    return true;
}

namespace {

// The constants of the clear and downsampling passes: one box of one level.
struct BoxConstants {
    glm::ivec4 minLevel, size;
    glm::uvec4 params;
};

}  // namespace

std::unique_ptr<Clipmap> Clipmap::create(rhi::IDevice& device, const ClipmapDesc& desc, Error* error) {
    const bricklight::detail::Refusal fail(error, "clip-map");
    std::optional<ClipmapPlacement> placement = ClipmapPlacement::create(desc, error);
    if (!placement) return nullptr;
    const rhi::Limits& limits = device.capabilities().limits;
    const uint32_t regions = detail::atlasRegions(desc.emittance);
    const uint64_t width = uint64_t(regions) * detail::regionWidth(desc.resolution);
    const uint64_t depth = detail::tracedSlices(desc.levels, desc.resolution);
    if (width > limits.maxTextureSize3D || depth > limits.maxTextureSize3D)
        return fail("the atlas (" + std::to_string(width) + " × " + std::to_string(desc.resolution) + " × " + std::to_string(depth) +
                    ") exceeds the device's 3D texture size of " + std::to_string(limits.maxTextureSize3D) + ": use fewer levels or a lower resolution", ErrorCode::OverBudget);
    const uint64_t lightBytes = std::max<uint64_t>(detail::lightEntriesPerPool(desc) * detail::kLightPools * 16, 16);
    if (lightBytes > limits.maxStorageBufferRange)
        return fail("the light pool (" + std::to_string(lightBytes >> 20) + " MiB) exceeds the device's storage buffer range of " +
                    std::to_string(limits.maxStorageBufferRange >> 20) + " MiB: lower lightEntries", ErrorCode::OverBudget);
    shaders::link_bricklight_vct();
    std::unique_ptr<Clipmap> c(new Clipmap(device, *placement));
    c->clearBoxes_ = shaders::createCoreShader(device, "vct/clear_boxes.comp");
    c->resolve_ = shaders::createCoreShader(device, "vct/resolve_light.comp");
    c->downsample_ = shaders::createCoreShader(device, "vct/downsample.comp");
    c->borders_ = shaders::createCoreShader(device, "vct/borders.comp");
    c->debugView_ = shaders::createCoreShader(device, "vct/debug_view.comp");
    const char* mips = desc.emittance == EmittanceMode::Anisotropic ? "vct/mip_build_anisotropic.comp"
                       : desc.emittance == EmittanceMode::Isotropic ? "vct/mip_build_isotropic.comp"
                                                                    : "vct/mip_build_opacity.comp";
    c->mipBuild_ = shaders::createCoreShader(device, mips);
    if (device.capabilities().geometryShader) {
        c->voxelizeGeometry_ = shaders::createCoreShader(device, "vct/voxelize.geom");
        c->voxelizeOpacity_ = shaders::createCoreShader(device, "vct/voxelize_opacity.frag");
    }
    // One R32_UINT texture for everything the voxelization writes (a draw has one storage image slot of ours):
    // RGB9E5_FLOAT is never storage-capable, so radiance is written as packed bits (bricklight/rgb9e5.glsl) and
    // sampled through an RGB9E5 view (a shared exponent keeps grey grey, where R11G11B10's 5-bit blue mantissa
    // tints it); opacity through an RGBA8_UNORM view.
    rhi::TextureDesc td;
    td.dimension = rhi::TextureDimension::Texture3D;
    td.format = rhi::Format::R32_UINT;
    td.width = uint32_t(width);
    td.height = desc.resolution;
    td.depthOrLayers = uint32_t(depth);
    td.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    td.debugName = "vct atlas";
    c->atlas_[0] = device.createTexture(td);
    if (desc.multiBounce) {
        td.debugName = "vct atlas (bounce)";
        c->atlas_[1] = device.createTexture(td);
    } else {
        td.width = td.height = td.depthOrLayers = 1;
        td.debugName = "vct no bounce";
        c->noBounce_ = device.createTexture(td);
    }
    rhi::SamplerDesc sampler;
    sampler.addressV = rhi::AddressMode::Repeat;  // toroidal in y; x and z have border columns and slices
    sampler.mipFilter = rhi::Filter::Nearest;
    sampler.debugName = "vct atlas";
    c->tracedSampler_ = device.createSampler(sampler);
    rhi::TextureDesc rd;
    rd.format = rhi::Format::D32_FLOAT;
    rd.width = rd.height = desc.resolution;
    rd.usage = rhi::TextureUsage::DepthTarget;
    rd.debugName = "vct raster size";
    c->rasterSize_ = device.createTexture(rd);
    rhi::BufferDesc bd;
    bd.size = lightBytes;
    bd.usage = rhi::BufferUsage::ShaderWrite | rhi::BufferUsage::ShaderRead;
    bd.debugName = "vct light";
    c->light_ = device.createBuffer(bd);
    bd.size = detail::kFrameBufferBytes;
    bd.usage = rhi::BufferUsage::ShaderRead;
    bd.debugName = "vct frame";
    c->frame_ = device.createBuffer(bd);
    bd.size = detail::kCounterWords * 4;
    bd.usage = rhi::BufferUsage::ShaderWrite;
    bd.debugName = "vct counters";
    c->counters_ = device.createBuffer(bd);
    const bool bounce = desc.multiBounce ? bool(c->atlas_[1]) : bool(c->noBounce_);
    if (!c->clearBoxes_ || !c->resolve_ || !c->light_ || !c->downsample_ || !c->borders_ || !c->mipBuild_ || !c->debugView_ || !c->atlas_[0] || !bounce ||
        !c->tracedSampler_ || !c->rasterSize_ || !c->frame_ || !c->counters_)
        return fail("the device could not create the clip-map's atlas, buffers or passes", ErrorCode::DeviceFailure);
    // A new texture's contents are undefined, and a direction word that happened to look like a tagged light entry
    // would send the voxelization's adds to an arbitrary index: zero once (later updates leave only radiance and
    // entries of their own). The bounce source is read before any frame wrote it: zero too. The light pool starts
    // zero; each update's resolve zeroes the entries it reads.
    if (!device.clearTexture(c->atlas_[0], 0, 1, rhi::ClearValue{}) ||
        !device.clearTexture(desc.multiBounce ? c->atlas_[1] : c->noBounce_, 0, 1, rhi::ClearValue{}) ||
        !device.clearBuffer(c->light_, {}, 0u) || !device.clearBuffer(c->counters_, {}, 0u))
        return fail("the device could not clear the clip-map's bounce atlas, light pool or counters", ErrorCode::DeviceFailure);
    return c;
}

Clipmap::~Clipmap() {
    for (rhi::TextureHandle t : {atlas_[0], atlas_[1], noBounce_, rasterSize_})
        if (t) device_.destroy(t);
    if (tracedSampler_) device_.destroy(tracedSampler_);
    for (rhi::BufferHandle b : {light_, frame_, counters_})
        if (b) device_.destroy(b);
    for (rhi::ShaderHandle s : {clearBoxes_, resolve_, downsample_, borders_, mipBuild_, voxelizeGeometry_, voxelizeOpacity_, debugView_})
        if (s) device_.destroy(s);
}

std::optional<std::vector<LevelUpdate>> Clipmap::update(const glm::vec3& anchor, Error* error,
                                                        const std::vector<WorldBox>& invalidated) {
    for (size_t i = 0; i < invalidated.size(); ++i) {
        const WorldBox& w = invalidated[i];
        bool finite = true;
        for (int a = 0; a < 3; ++a) finite = finite && std::isfinite(w.min[a]) && std::isfinite(w.max[a]);
        if (!finite) {
            if (error) *error = {ErrorCode::InvalidArgument, "clip-map: invalidated box " + std::to_string(i) + " is not finite"};
            return std::nullopt;
        }
    }
    const ClipmapDesc& d = desc();
    std::vector<glm::ivec3> before(d.levels);
    for (uint32_t level = 0; level < d.levels; ++level) before[level] = placement_.origin(level);
    const bool placedBefore = placement_.placed();
    std::optional<std::vector<LevelUpdate>> updates = placement_.moveAnchor(anchor, error);
    if (!updates) return std::nullopt;
    detail::FrameRegions regions = detail::frameRegions(d, before, placedBefore, *updates, invalidated);
    rewrite_ = std::move(regions.rewrite);
    downsampleBoxes_ = std::move(regions.downsample);
    // A pass per box, whole levels too: a fill of the whole 3D atlas is far slower than the pass on NVIDIA's driver
    // (docs/notes/vct-memory.md). The mips' slab and the borders need no clear: every texel of them that is read is
    // rewritten by finishVoxelization().
    for (const LevelBox& b : rewrite_) clearBox(b);
    // The light pool's claim counters and the dropped-light count start over.
    device_.clearBuffer(counters_, rhi::BufferRange{detail::kLightDroppedWord * 4, (detail::kCounterWords - detail::kLightDroppedWord) * 4}, 0u);
    writeFrame();
    return updates;
}

void Clipmap::clearBox(const LevelBox& b) {
    const glm::ivec3 size = b.box.max - b.box.min;
    // The opacity only: the directions' words are overwritten by the resolve (vctTagLightEntry).
    BoxConstants c{glm::ivec4(b.box.min, int(b.level)), glm::ivec4(size, 0), glm::uvec4(desc().resolution, 0u, 0u, 0u)};
    rhi::DispatchState s;
    s.shader = clearBoxes_;
    s.label = "vct clear voxels";
    s.bindings.constants.push(rhi::constants(0, c));
    s.bindings.storageImages.push(rhi::storageImage(0, atlas(), rhi::Access::Write));
    device_.dispatch(s, uint32_t(size.x + 31) / 32, uint32_t(size.y + 1) / 2, uint32_t(size.z));  // 32 × 2 × 1 groups
}

void Clipmap::writeFrame() {
    const ClipmapDesc& d = desc();
    std::vector<uint8_t> bytes(sizeof(detail::FrameHeader) + rewrite_.size() * sizeof(detail::FrameBox));
    detail::FrameHeader h{};
    for (uint32_t level = 0; level < d.levels; ++level) h.origin[level] = glm::ivec4(placement_.origin(level), 0);
    h.params = glm::uvec4(d.resolution, d.levels, emittanceDirections(d.emittance), uint32_t(rewrite_.size()));
    h.scales = glm::vec4(d.finestVoxelSize, detail::kEmittanceUnits * d.emittanceStorageScale, 0.0f, 0.0f);
    h.flags = glm::uvec4(countersEnabled_ ? 1u : 0u, clipmapMipLevels(d), uint32_t(detail::lightEntriesPerPool(d)), 0u);
    std::memcpy(bytes.data(), &h, sizeof(h));
    for (size_t i = 0; i < rewrite_.size(); ++i) {
        const detail::FrameBox b{glm::ivec4(rewrite_[i].box.min, int(rewrite_[i].level)), glm::ivec4(rewrite_[i].box.max, 0)};
        std::memcpy(bytes.data() + sizeof(h) + i * sizeof(b), &b, sizeof(b));
    }
    device_.writeBuffer(frame_, 0, bytes.data(), bytes.size());
}

std::optional<rhi::DrawCallState> Clipmap::voxelizationState(const VoxelMaterial& material, Error* error) {
    if (!checkVoxelMaterial(material, error)) return std::nullopt;
    if (!voxelizeGeometry_ || !voxelizeOpacity_) {
        if (error) *error = {ErrorCode::Unsupported, "clip-map: voxelization needs geometry shaders, which the device does not offer"};
        return std::nullopt;
    }
    const MaterialBlock block{{material.thickness, material.opacity, material.twoSided ? 1.0f : 0.0f, 0.0f}};
    const MaterialBlock* constants = nullptr;
    for (const auto& m : materials_)
        if (std::memcmp(m->values, block.values, sizeof(block.values)) == 0) constants = m.get();
    if (!constants) {
        constexpr size_t kMaxMaterials = 4096;
        if (materials_.size() >= kMaxMaterials) {
            if (error) *error = {ErrorCode::OverBudget, "clip-map: more than " + std::to_string(kMaxMaterials) + " distinct voxel materials"};
            return std::nullopt;
        }
        materials_.push_back(std::make_unique<MaterialBlock>(block));
        constants = materials_.back().get();
    }
    const uint32_t resolution = desc().resolution;
    rhi::DrawCallState s;
    s.geometryShader = voxelizeGeometry_;
    s.fragmentShader = material.fragmentShader ? material.fragmentShader : voxelizeOpacity_;
    s.topology = rhi::PrimitiveTopology::TriangleList;
    s.depthTarget.view = rhi::textureMip(rasterSize_, 0);
    s.depthTarget.load = rhi::LoadOp::DontCare;
    s.viewport = rhi::Viewport{0.0f, 0.0f, float(resolution), float(resolution), 0.0f, 1.0f};
    s.raster.cull = rhi::CullMode::None;
    s.label = "vct voxelize";
    s.bindings.constants.push(rhi::ConstantsBinding{VoxelizationSlots::kMaterialConstants, constants->values, uint32_t(sizeof(block.values))});
    rhi::ReadBufferBinding frame;
    frame.slot = VoxelizationSlots::kFrameReadBuffer;
    frame.buffer = frame_;
    s.bindings.readBuffers.push(frame);
    rhi::StorageBufferBinding light;
    light.slot = VoxelizationSlots::kLightBuffer;
    light.buffer = light_;
    light.access = rhi::Access::Atomic;
    s.bindings.storageBuffers.push(light);
    rhi::StorageBufferBinding counters = light;
    counters.slot = VoxelizationSlots::kCountersBuffer;
    counters.buffer = counters_;
    s.bindings.storageBuffers.push(counters);
    s.bindings.storageImages.push(rhi::storageImage(VoxelizationSlots::kAtlasImage, atlas(), rhi::Access::Atomic));
    return s;
}

void Clipmap::downsampleBox(const LevelBox& b) {
    const glm::ivec3 size = b.box.max - b.box.min;
    BoxConstants c{glm::ivec4(b.box.min, int(b.level)), glm::ivec4(size, 0), glm::uvec4(desc().resolution, emittanceDirections(desc().emittance), 0u, 0u)};
    rhi::DispatchState s;
    s.shader = downsample_;
    s.label = "vct downsample";
    s.bindings.constants.push(rhi::constants(0, c));
    s.bindings.storageImages.push(rhi::storageImage(0, atlas(), rhi::Access::ReadWrite));
    device_.dispatch(s, uint32_t(size.x + 31) / 32, uint32_t(size.y + 1) / 2, uint32_t(size.z));  // 32 × 2 × 1 groups
}

void Clipmap::copyBorders(uint32_t level) {
    const uint32_t r = desc().resolution, regions = detail::atlasRegions(desc().emittance);
    const glm::uvec4 c(r, level, regions, 0u);
    rhi::DispatchState s;
    s.shader = borders_;
    s.label = "vct borders";
    s.bindings.constants.push(rhi::constants(0, c));
    s.bindings.storageImages.push(rhi::storageImage(0, atlas(), rhi::Access::ReadWrite));
    device_.dispatch(s, (r + 2 + 31) / 32, (r + 1) / 2, 4 * regions);  // faces × regions in z
}

void Clipmap::resolveBox(const LevelBox& b) {
    const glm::ivec3 size = b.box.max - b.box.min;
    struct {
        glm::ivec4 minLevel, size;
        glm::uvec4 params;
        glm::vec4 scales;
    } c{glm::ivec4(b.box.min, int(b.level)), glm::ivec4(size, 0), glm::uvec4(desc().resolution, emittanceDirections(desc().emittance), 0u, 0u),
        glm::vec4(1.0f / (detail::kEmittanceUnits * desc().emittanceStorageScale), 0.0f, 0.0f, 0.0f)};
    rhi::DispatchState s;
    s.shader = resolve_;
    s.label = "vct resolve";
    s.bindings.constants.push(rhi::constants(0, c));
    s.bindings.storageImages.push(rhi::storageImage(0, atlas(), rhi::Access::ReadWrite));
    rhi::StorageBufferBinding light;
    light.slot = 0;
    light.buffer = light_;
    light.access = rhi::Access::ReadWrite;
    s.bindings.storageBuffers.push(light);
    device_.dispatch(s, uint32_t(size.x + 31) / 32, uint32_t(size.y + 1) / 2, uint32_t(size.z));  // 32 × 2 × 1 groups
}

void Clipmap::finishVoxelization() {
    // The light the draws gathered becomes radiance first: the downsampling reads the finer levels' radiance. Each
    // voxel once (a resolved word is radiance, no longer an entry): the rewrite boxes may overlap (what entered a
    // level and an invalidated box), so they are cut into disjoint pieces.
    device_.beginMarker("vct resolve");
    if (desc().emittance != EmittanceMode::None) {
        std::vector<LevelBox> disjoint;
        for (const LevelBox& b : rewrite_) {
            std::vector<VoxelBox> pieces{b.box};
            for (const LevelBox& earlier : disjoint) {
                if (earlier.level != b.level) continue;
                std::vector<VoxelBox> outside;
                for (const VoxelBox& p : pieces)
                    for (const VoxelBox& s : detail::uncovered(earlier.box, p)) outside.push_back(s);
                pieces = std::move(outside);
            }
            for (const VoxelBox& p : pieces) disjoint.push_back({b.level, p});
        }
        for (const LevelBox& b : disjoint) resolveBox(b);
    }
    device_.endMarker();
    device_.beginMarker("vct downsample");
    for (const LevelBox& b : downsampleBoxes_) downsampleBox(b);
    device_.endMarker();
    // The border columns and slices of every level that changed.
    std::vector<bool> changed(desc().levels, false);
    for (const std::vector<LevelBox>* boxes : {&rewrite_, &downsampleBoxes_})
        for (const LevelBox& b : *boxes) changed[b.level] = true;
    device_.beginMarker("vct borders");
    for (uint32_t level = 0; level < desc().levels; ++level)
        if (changed[level]) copyBorders(level);
    device_.endMarker();
    if (changed[desc().levels - 1]) buildMips();
    // Multiple bounces: the next frame's draws read this frame's light from a copy while they write the atlas.
    if (desc().multiBounce) device_.copyTexture(atlas_[1], {}, atlas_[0], {});
}

// The mips are small (the first has an eighth of a level's voxels) and rebuilt whole whenever the coarsest level
// changed: what a change touches there spreads over most of them anyway.
void Clipmap::buildMips() {
    const ClipmapDesc& d = desc();
    const uint32_t coarsest = d.levels - 1, mips = clipmapMipLevels(d);
    const int r = int(d.resolution);
    const glm::ivec3 origin = placement_.origin(coarsest);
    struct {
        glm::ivec4 target, targetMin, source, sourceMin, shift;
    } c;
    device_.beginMarker("vct mips");
    for (uint32_t m = 1; m <= mips; ++m) {
        const int size = detail::mipBoxSize(m, d.resolution);
        c.target = glm::ivec4(detail::mipBoxOffset(m, d.levels, d.resolution), size);
        c.targetMin = glm::ivec4((origin >> int(m)) - 1, 0);
        if (m == 1) {  // the coarsest level, toroidal: its first voxel is stored at the origin modulo the resolution
            c.source = glm::ivec4(0, 0, int(coarsest) * (r + 2) + 1, r);
            c.sourceMin = glm::ivec4(origin, 0);
            c.shift = glm::ivec4(placement_.toroidalTexel(origin), r);
        } else {
            c.source = glm::ivec4(detail::mipBoxOffset(m - 1, d.levels, d.resolution), detail::mipBoxSize(m - 1, d.resolution));
            c.sourceMin = glm::ivec4((origin >> int(m - 1)) - 1, 0);
            c.shift = glm::ivec4(0, 0, 0, r);
        }
        rhi::DispatchState s;
        s.shader = mipBuild_;
        s.label = "vct mip";
        s.bindings.constants.push(rhi::constants(0, c));
        s.bindings.storageImages.push(rhi::storageImage(0, atlas(), rhi::Access::ReadWrite));
        const uint32_t groups = uint32_t(size + 3) / 4;
        device_.dispatch(s, groups, groups, groups);
    }
    device_.endMarker();
}

bool Clipmap::debugView(const DebugViewDesc& d, Error* error) {
    const bricklight::detail::Refusal fail(error, "clip-map debug view");
    if (uint32_t(d.mode) > uint32_t(DebugMode::Rewritten)) return fail("mode " + std::to_string(uint32_t(d.mode)) + " is not a DebugMode");
    const int32_t lastLevel = int32_t(desc().levels - 1 + clipmapMipLevels(desc()));  // the coarsest level's mips follow it
    if (d.level < -1 || d.level > lastLevel)
        return fail("level " + std::to_string(d.level) + " is outside -1.." + std::to_string(lastLevel) + " (levels, then the coarsest level's mips)");
    if (d.direction < -1 || d.direction > 5) return fail("direction " + std::to_string(d.direction) + " is outside -1..5");
    if (!(d.exposure > 0.0f) || !std::isfinite(d.exposure)) return fail("exposure must be a positive finite number");
    const rhi::TextureDesc* out = device_.describe(d.output);
    if (!out || out->format != rhi::Format::RGBA8_UNORM || !(out->usage & rhi::TextureUsage::Storage))
        return fail("the output must be a live RGBA8_UNORM texture with Storage usage", ErrorCode::WrongFormat);
    if (!placement_.placed()) return fail("the clip-map has not been placed yet (update() first)", ErrorCode::InvalidState);
    struct {
        glm::mat4 inverseViewProjection;
        glm::vec4 eye;
        glm::uvec4 size;
        glm::ivec4 face;
    } c{glm::inverse(d.projection * d.view), glm::vec4(d.cameraPosition, d.exposure),
        glm::uvec4(out->width, out->height, uint32_t(d.mode), d.level < 0 ? 0xFFFFFFFFu : uint32_t(d.level)), glm::ivec4(d.direction, 0, 0, 0)};
    rhi::DispatchState s;
    s.shader = debugView_;
    s.label = "vct debug view";
    s.bindings.constants.push(rhi::constants(0, c));
    traceBindings(s.bindings);
    s.bindings.storageImages.push(rhi::storageImage(0, d.output, rhi::Access::Write));
    return device_.dispatch(s, (out->width + 7) / 8, (out->height + 7) / 8, 1);
}

void Clipmap::bindAtlas(rhi::Bindings& bindings, rhi::TextureHandle texture, uint8_t textureBase, uint8_t frameSlot) const {
    rhi::TextureView opacity = rhi::wholeTexture(texture), radiance = opacity;
    opacity.format = rhi::Format::RGBA8_UNORM;
    radiance.format = rhi::Format::RGB9E5_FLOAT;
    bindings.textures.push(rhi::TextureBinding{textureBase, opacity, tracedSampler_});
    bindings.textures.push(rhi::TextureBinding{uint8_t(textureBase + 1), radiance, tracedSampler_});
    for (const rhi::ReadBufferBinding& b : bindings.readBuffers)
        if (b.slot == frameSlot && b.buffer == frame_) return;  // a voxelization record has it already
    bindings.readBuffers.push(rhi::ReadBufferBinding{frameSlot, frame_, {}});
}

void Clipmap::traceBindings(rhi::Bindings& bindings, uint8_t textureBase, uint8_t frameSlot) const {
    bindAtlas(bindings, atlas(), textureBase, frameSlot);
}

void Clipmap::bounceBindings(rhi::Bindings& bindings, uint8_t textureBase, uint8_t frameSlot) const {
    bindAtlas(bindings, desc().multiBounce ? atlas_[1] : noBounce_, textureBase, frameSlot);
}

std::vector<WorldBox> Clipmap::dirtyRegions() const {
    std::vector<WorldBox> regions;
    for (const LevelBox& b : rewrite_) {
        const float size = placement_.voxelSize(b.level);
        regions.push_back({glm::vec3(b.box.min) * size, glm::vec3(b.box.max) * size});
    }
    return regions;
}

void Clipmap::setCountersEnabled(bool enabled) {
    countersEnabled_ = enabled;
    if (placement_.placed()) writeFrame();
}

// The statistics only: the light pool's claim counters belong to the update (clearing them between the draws and
// finishVoxelization() would hand out entries twice).
void Clipmap::resetCounters() { device_.clearBuffer(counters_, rhi::BufferRange{0, detail::kLightDroppedWord * 4}, 0u); }

VoxelizationCounters Clipmap::readCounters() {
    uint32_t words[detail::kCounterWords] = {};
    VoxelizationCounters c;
    if (!device_.readBuffer(counters_, 0, sizeof(words), words)) return c;
    c.fragments = words[0];
    c.offTriangle = words[1];
    c.voxelsWritten = words[2];
    c.killedByFiner = words[3];
    c.killedNotDirty = words[4];
    c.emittanceWrites = words[5];
    c.lightDropped = words[6];
    const uint64_t perPool = detail::lightEntriesPerPool(desc());
    for (uint32_t p = 0; p < detail::kLightPools; ++p) c.lightEntriesClaimed += std::min<uint64_t>(words[detail::kStatisticWords + p], perPool);
    c.lightEntriesAvailable = perPool * detail::kLightPools;
    return c;
}

MemoryUse Clipmap::memoryUse() const {
    MemoryUse use;
    auto add = [&](const std::string& name, uint64_t bytes) {
        use.resources.push_back({name, bytes});
        use.totalBytes += bytes;
    };
    for (rhi::TextureHandle t : {atlas_[0], atlas_[1], noBounce_, rasterSize_})
        if (const rhi::TextureDesc* d = device_.describe(t)) add(d->debugName, rhi::subresourceBytes(*d, {}));
    for (rhi::BufferHandle b : {light_, frame_, counters_})
        if (const rhi::BufferDesc* d = device_.describe(b)) add(d->debugName, d->size);
    return use;
}

}  // namespace bricklight::vct
