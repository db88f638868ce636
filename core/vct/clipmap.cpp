// vct::Clipmap: the clip-map's volumes on a device, cleared where the levels scroll.
#include "bricklight/vct.h"
#include "../core_shaders.h"

namespace bricklight::vct {

std::unique_ptr<Clipmap> Clipmap::create(rhi::IDevice& device, const ClipmapDesc& desc, std::string* error) {
    auto fail = [&](const std::string& why) {
        if (error) *error = "clip-map: " + why;
        return nullptr;
    };
    std::optional<ClipmapPlacement> placement = ClipmapPlacement::create(desc, error);
    if (!placement) return nullptr;
    const rhi::Limits& limits = device.capabilities().limits;
    const uint64_t depth = uint64_t(desc.resolution) * desc.levels;
    if (desc.resolution > limits.maxTextureSize3D || depth > limits.maxTextureSize3D)
        return fail("the opacity volume (" + std::to_string(desc.resolution) + "² × " + std::to_string(depth) +
                    ") exceeds the device's 3D texture size of " + std::to_string(limits.maxTextureSize3D) + ": use fewer levels or a lower resolution");
    shaders::link_bricklight_core();
    std::unique_ptr<Clipmap> c(new Clipmap(device, *placement));
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("vct/clear_boxes.comp");
    c->clearBoxes_ = sd.blob ? device.createShader(sd) : rhi::ShaderHandle{};
    rhi::TextureDesc td;
    td.dimension = rhi::TextureDimension::Texture3D;
    td.format = rhi::Format::R32_UINT;
    td.width = td.height = desc.resolution;
    td.depthOrLayers = uint32_t(depth);
    td.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    td.debugName = "vct opacity";
    c->opacity_ = device.createTexture(td);
    if (!c->clearBoxes_ || !c->opacity_) return fail("the device could not create the opacity volume or its clear pass");
    return c;
}

Clipmap::~Clipmap() {
    if (opacity_) device_.destroy(opacity_);
    if (clearBoxes_) device_.destroy(clearBoxes_);
}

std::optional<std::vector<LevelUpdate>> Clipmap::update(const glm::vec3& anchor, std::string* error) {
    std::optional<std::vector<LevelUpdate>> updates = placement_.moveAnchor(anchor, error);
    if (!updates) return std::nullopt;
    const uint32_t resolution = placement_.desc().resolution;
    for (const LevelUpdate& u : *updates)
        for (const VoxelBox& b : u.entered) {
            const glm::ivec3 size = b.max - b.min;
            struct {
                glm::ivec4 minLevel, size;
                glm::uvec4 params;
            } c{glm::ivec4(b.min, int(u.level)), glm::ivec4(size, 0), glm::uvec4(resolution, 0u, 0u, 0u)};
            rhi::DispatchState s;
            s.shader = clearBoxes_;
            s.label = "vct clear entered voxels";
            s.bindings.constants.push(rhi::constants(0, c));
            rhi::StorageImageBinding volume;
            volume.slot = 0;
            volume.view = rhi::textureMip(opacity_, 0);
            volume.access = rhi::Access::Write;
            s.bindings.storageImages.push(volume);
            device_.dispatch(s, uint32_t(size.x + 3) / 4, uint32_t(size.y + 3) / 4, uint32_t(size.z + 3) / 4);
        }
    return updates;
}

MemoryUse Clipmap::memoryUse() const {
    MemoryUse use;
    if (const rhi::TextureDesc* d = device_.describe(opacity_)) {
        use.resources.push_back({d->debugName, rhi::subresourceBytes(*d, {})});
        use.totalBytes += use.resources.back().bytes;
    }
    return use;
}

}  // namespace bricklight::vct
