// The debug views (shaders/gi/debug_view.comp) of the latest dispatch.
#include "gi_context_impl.h"

namespace bricklight::gi::detail {

bool GiContextImpl::debugView(const DebugViewDesc& desc) {
    if (!sceneAlive()) return false;
    if (uint32_t(desc.mode) > uint32_t(DebugMode::SampleCount)) return fail(ErrorCode::InvalidArgument, "debugView: unknown mode " + std::to_string(uint32_t(desc.mode)));
    const rhi::TextureDesc* td = desc.output ? device_.describe(desc.output) : nullptr;
    if (!td) return fail(ErrorCode::InvalidHandle, "debugView: output is missing or not a live texture");
    if (td->dimension != rhi::TextureDimension::Texture2D || td->format != rhi::Format::RGBA8_UNORM || !(td->usage & rhi::TextureUsage::Storage))
        return fail(ErrorCode::WrongFormat, "debugView: output '" + td->debugName + "' must be a 2D RGBA8_UNORM texture with Storage usage");
    if (td->width != desc_.displayWidth || td->height != desc_.displayHeight)
        return fail(ErrorCode::WrongSize, "debugView: output '" + td->debugName + "' must be the display size");
    if (!(desc.exposure > 0.0f)) return fail(ErrorCode::InvalidArgument, "debugView: exposure must be > 0");
    if (!historyValid_) return fail(ErrorCode::InvalidState, "debugView: nothing to show before the first dispatch");
    const int cur = lastFrame_;
    struct {
        uint32_t mode[4];
        float exposure[4];
    } pass{{uint32_t(desc.mode), 0, 0, 0}, {desc.exposure, 0, 0, 0}};
    rhi::DispatchState s;
    s.bindings.constants.push(rhi::constants(2, pass));
    texture(s.bindings, 0, depth_[cur], point_);
    texture(s.bindings, 1, surface_[cur], point_);
    texture(s.bindings, 2, probes_[cur], point_);
    texture(s.bindings, 3, disocclusion_, point_);
    texture(s.bindings, 4, diffuseHistory_[cur], point_);
    readBuffer(s.bindings, 0, probeInfo_[cur]);
    readBuffer(s.bindings, 1, probeSH_);
    readBuffer(s.bindings, 2, brickSH_);
    image(s.bindings, 0, desc.output, rhi::Access::Write);
    image(s.bindings, 1, radianceCache_, rhi::Access::Read);
    readBuffer(s.bindings, 3, slotOfBrick_);
    addTrace(s.bindings);
    run("gi debug view", shaders_.debug, s, (desc_.displayWidth + 7) / 8, (desc_.displayHeight + 7) / 8);
    return true;
}

}  // namespace bricklight::gi::detail
