// Declared accesses of one call -> one vkCmdPipelineBarrier2 (rules in vk_barriers.h).
#include <algorithm>

#include "vk_device.h"

namespace bricklight::vulkan::detail {

void VulkanDevice::recordBarriers(VkCommandBuffer c, const CallPlan& planIn) {
    BarrierBatch batch;
    for (const auto& u : planIn.buffers) {
        BarrierNeed need = computeBarrier(u.buffer->state, u.request, false);
        if (need.needed) batch.buffer(u.buffer->buffer, need, u.request);
        applyAccess(u.buffer->state, u.request, need, false);
    }
    // Subresources in (texture, mip, layer) order so that neighbouring layers with the same barrier merge.
    std::vector<const CallPlan::TextureUse*> uses;
    uses.reserve(planIn.textures.size());
    for (const auto& u : planIn.textures) uses.push_back(&u);
    std::sort(uses.begin(), uses.end(), [](const CallPlan::TextureUse* a, const CallPlan::TextureUse* b) {
        if (a->texture->id != b->texture->id) return a->texture->id < b->texture->id;
        if (a->mip != b->mip) return a->mip < b->mip;
        return a->layer < b->layer;
    });
    struct Run {
        const CallPlan::TextureUse* first = nullptr;
        uint32_t layers = 0;
        BarrierNeed need;
    } run;
    auto emit = [&] {
        if (run.first && run.need.needed)
            batch.image(run.first->texture->image, run.first->texture->aspect, run.first->mip, run.first->layer,
                        run.layers, run.need, run.first->request);
        run = Run{};
    };
    for (const CallPlan::TextureUse* u : uses) {
        AccessState& state = u->texture->sub(u->mip, u->layer);
        BarrierNeed need = computeBarrier(state, u->request, true);
        const bool extends = run.first && run.first->texture == u->texture && run.first->mip == u->mip &&
                             run.first->layer + run.layers == u->layer && run.need == need &&
                             run.first->request.stages == u->request.stages &&
                             run.first->request.access == u->request.access &&
                             run.first->request.layout == u->request.layout;
        if (extends) {
            run.layers++;
        } else {
            emit();
            run.first = u;
            run.layers = 1;
            run.need = need;
        }
        applyAccess(state, u->request, need, true);
    }
    emit();
    barrierCount_ += batch.flush(c);
}

void VulkanDevice::releaseWrapped(VkCommandBuffer c, const CallPlan& plan) {
    // Wrapped objects go back to the application after every call: made available to any later command
    // and (images) returned to the layout the application gave.
    BarrierBatch batch;
    AccessRequest any;
    any.stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    any.access = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    any.write = true;
    any.shaderWriteOnly = false;
    for (const auto& u : plan.buffers) {
        if (!u.buffer->wrapped) continue;
        AccessState& s = u.buffer->state;
        BarrierNeed need;
        need.needed = true;
        need.srcStages = s.writeStages | s.readStages;
        need.srcAccess = s.writeAccess;
        batch.buffer(u.buffer->buffer, need, any);
        s = AccessState{};
        s.writeStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        s.writeAccess = VK_ACCESS_2_MEMORY_WRITE_BIT;
    }
    for (const auto& u : plan.textures) {
        Texture& t = *u.texture;
        if (!t.wrapped || t.nativeLayout == VK_IMAGE_LAYOUT_UNDEFINED) continue;
        AccessState& s = t.sub(u.mip, u.layer);
        BarrierNeed need;
        need.needed = true;
        need.srcStages = s.writeStages | s.readStages;
        need.srcAccess = s.writeAccess;
        need.oldLayout = s.layout;
        any.layout = t.nativeLayout;
        batch.image(t.image, t.aspect, u.mip, u.layer, 1, need, any);
        s = AccessState{};
        s.layout = t.nativeLayout;
        s.writeStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        s.writeAccess = VK_ACCESS_2_MEMORY_WRITE_BIT;
    }
    barrierCount_ += batch.flush(c);
}

}  // namespace bricklight::vulkan::detail
