// The trace bindings a caller merges into its record, and the debug view pass (one traced ray per pixel).
#include <glm/gtc/matrix_inverse.hpp>

#include "../common/finite_checks.h"
#include "sdf_scene_impl.h"

namespace bricklight::sdf::detail {

void SdfSceneImpl::traceBindings(rhi::Bindings& b, TraceSlots slots) const {
    b.textures.push({slots.atlasTexture, rhi::wholeTexture(atlas_), atlasSampler_});
    b.readBuffers.push({uint8_t(slots.readBufferBase + 0), cascadeTable_, {}});
    b.readBuffers.push({uint8_t(slots.readBufferBase + 1), brickMaps_, {}});
    b.readBuffers.push({uint8_t(slots.readBufferBase + 2), trees_, {}});
    b.readBuffers.push({uint8_t(slots.readBufferBase + 3), brickAabbs_, {}});
}

bool SdfSceneImpl::debugView(const DebugViewDesc& d) {
    const rhi::TextureDesc* out = device_.describe(d.output);
    if (!out) return fail(ErrorCode::InvalidHandle, "debugView: output is not a live texture");
    if (out->dimension != rhi::TextureDimension::Texture2D || out->format != rhi::Format::RGBA8_UNORM ||
        !(out->usage & rhi::TextureUsage::Storage))
        return fail(ErrorCode::WrongFormat, "debugView: output '" + out->debugName + "' must be a 2D RGBA8_UNORM texture with Storage usage");
    if (uint32_t(d.mode) > uint32_t(DebugMode::Uvw)) return fail(ErrorCode::InvalidArgument, "debugView: unknown mode " + std::to_string(uint32_t(d.mode)));
    const glm::mat4 viewProjection = d.projection * d.view;
    const glm::mat4 inverse = glm::inverse(viewProjection);
    if (!bricklight::detail::finite(inverse)) return fail(ErrorCode::InvalidArgument, "debugView: view * projection is not invertible");

    // Overlay boxes: cascades (colour index = cascade), then instances.
    std::vector<glm::vec4> boxes;
    const uint32_t capacity = std::max(1u, desc_.maxBoundsOverlays);
    if (d.showCascadeBounds)
        for (uint32_t c = 0; c < desc_.cascadeCount && boxes.size() / 2 < capacity; ++c) {
            const float vs = voxelSize(c);
            boxes.push_back(glm::vec4(glm::vec3(cascades_[c].origin) * vs, float(c)));
            boxes.push_back(glm::vec4(glm::vec3(cascades_[c].origin + int(kCascadeResolution)) * vs, 0.0f));
        }
    if (d.showInstanceBounds)
        for (const auto& [id, inst] : instances_) {
            if (boxes.size() / 2 >= capacity) break;
            boxes.push_back(glm::vec4(inst.bounds.min, float(100 + (inst.dynamic ? 1 : 0))));
            boxes.push_back(glm::vec4(inst.bounds.max, 0.0f));
        }
    if (!boxes.empty()) device_.writeBuffer(overlays_, 0, boxes.data(), boxes.size() * sizeof(glm::vec4));

    struct {
        glm::mat4 inverseViewProjection;
        glm::vec4 eye;
        uint32_t size[4];
        uint32_t cascades[4];
        float range[4];
    } p{};
    p.inverseViewProjection = inverse;
    p.eye = glm::inverse(d.view)[3];
    p.size[0] = out->width;
    p.size[1] = out->height;
    p.size[2] = uint32_t(d.mode);
    p.size[3] = uint32_t(boxes.size() / 2);
    p.cascades[0] = d.startCascade;
    p.cascades[1] = std::min(d.endCascade, desc_.cascadeCount - 1);
    p.range[0] = d.tMin;
    p.range[1] = d.tMax;
    rhi::DispatchState s;
    s.shader = shaders_.debug;
    s.label = "sdf debug view";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.readBuffers.push({0, overlays_, {}});
    s.bindings.storageImages.push({0, rhi::wholeTexture(d.output), rhi::Access::Write});
    traceBindings(s.bindings, {});
    return device_.dispatch(s, (out->width + 7) / 8, (out->height + 7) / 8, 1);
}

}  // namespace bricklight::sdf::detail
