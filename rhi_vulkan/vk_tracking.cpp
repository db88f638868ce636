// Declared accesses of one call -> one vkCmdPipelineBarrier2 (rules in vk_barriers.h).
#include <algorithm>

#include "vk_device.h"

namespace bricklight::vulkan::detail {

void VulkanDevice::recordBarriers(VkCommandBuffer c, const CallPlan& planIn) {
    const uint64_t serial = ++callSerial_;
    const BarrierHistory* history = barrierReuse_ ? &history_ : nullptr;
    BarrierBatch batch;
    // Every dependency without a layout change goes into one global memory barrier. It also takes in
    // everything outstanding since the last barrier (pending*), which costs nothing more on hardware that
    // waits for whole stages anyway, and lets later calls find their hazards ordered already (history_).
    VkPipelineStageFlags2 srcStages = 0, dstStages = 0;
    VkAccessFlags2 srcAccess = 0;
    bool needed = false;
    auto take = [&](const BarrierNeed& need, const AccessRequest& request) {
        dstStages |= request.stages;
        if (!need.needed) return;
        needed = true;
        srcStages |= need.srcStages;
        srcAccess |= need.srcAccess;
    };
    std::vector<BarrierNeed> bufferNeeds(planIn.buffers.size());
    for (size_t i = 0; i < planIn.buffers.size(); ++i) {
        const auto& u = planIn.buffers[i];
        bufferNeeds[i] = computeBarrier(u.buffer->state, u.request, false, u.buffer->wrapped ? nullptr : history);
        take(bufferNeeds[i], u.request);
    }
    // Subresources in (texture, mip, layer) order so that neighbouring layers with the same transition
    // merge into one image barrier.
    std::vector<const CallPlan::TextureUse*> uses;
    uses.reserve(planIn.textures.size());
    for (const auto& u : planIn.textures) uses.push_back(&u);
    std::sort(uses.begin(), uses.end(), [](const CallPlan::TextureUse* a, const CallPlan::TextureUse* b) {
        if (a->texture->id != b->texture->id) return a->texture->id < b->texture->id;
        if (a->mip != b->mip) return a->mip < b->mip;
        return a->layer < b->layer;
    });
    std::vector<BarrierNeed> textureNeeds(uses.size());
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
    for (size_t i = 0; i < uses.size(); ++i) {
        const CallPlan::TextureUse* u = uses[i];
        const AccessState& state = u->texture->sub(u->mip, u->layer);
        BarrierNeed need = computeBarrier(state, u->request, true, u->texture->wrapped ? nullptr : history);
        textureNeeds[i] = need;
        if (need.oldLayout == u->request.layout) {  // no transition: part of the global barrier
            take(need, u->request);
            continue;
        }
        dstStages |= u->request.stages;
        srcStages |= need.srcStages;  // the global barrier orders the same work (it is a superset)
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
    }
    emit();
    if (needed || !batch.empty()) {
        if (barrierReuse_) {
            srcStages |= pendingStages_;
            srcAccess |= pendingWriteAccess_;
        }
        if (srcStages) {
            const VkAccessFlags2 dstAccess = srcAccess ? accessesOfStages(dstStages) : 0;
            batch.memory(srcStages, srcAccess, dstStages, dstAccess);
            if (barrierReuse_) history_.record({serial, srcStages, dstStages, srcAccess, dstAccess});
        }
        pendingStages_ = 0;
        pendingWriteAccess_ = 0;
    }
    // The call's own accesses come after its barrier.
    for (size_t i = 0; i < planIn.buffers.size(); ++i) {
        applyAccess(planIn.buffers[i].buffer->state, planIn.buffers[i].request, bufferNeeds[i], false, serial);
        notePending(planIn.buffers[i].request);
    }
    for (size_t i = 0; i < uses.size(); ++i) {
        applyAccess(uses[i]->texture->sub(uses[i]->mip, uses[i]->layer), uses[i]->request, textureNeeds[i], true, serial);
        notePending(uses[i]->request);
    }
    if (!batch.empty()) ++pipelineBarriers_;
    barrierCount_ += batch.flush(c);
}

void VulkanDevice::notePending(const AccessRequest& request) {
    pendingStages_ |= request.stages;
    if (request.write) pendingWriteAccess_ |= request.access & kWriteAccessBits;
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
