#include "vk_barriers.h"

namespace bricklight::vulkan::detail {

bool AccessRequest::merge(const AccessRequest& o) {
    if (layout != o.layout) return false;
    stages |= o.stages;
    access |= o.access;
    write = write || o.write;
    shaderWriteOnly = shaderWriteOnly && o.shaderWriteOnly;
    noBarrierWithPreviousWriter = noBarrierWithPreviousWriter && o.noBarrierWithPreviousWriter;
    return true;
}

namespace {
bool isVisible(const AccessState& s, VkPipelineStageFlags2 stages, VkAccessFlags2 access) {
    for (uint8_t i = 0; i < s.visibleCount; ++i)
        if ((s.visible[i].stages & stages) == stages && (s.visible[i].access & access) == access) return true;
    return false;
}
}  // namespace

BarrierNeed computeBarrier(const AccessState& s, const AccessRequest& r, bool image) {
    BarrierNeed n;
    n.oldLayout = s.layout;
    const VkAccessFlags2 readBits = r.access & ~kWriteAccessBits;
    if (image && r.layout != s.layout) {
        // The transition writes the image: it must wait for the last write (memory) and every reader
        // since (execution). From UNDEFINED with no history there is nothing to wait for.
        n.needed = true;
        n.srcStages = s.writeStages | s.readStages;
        n.srcAccess = s.writeAccess;
        return n;
    }
    if (r.write) {
        if (s.readStages) {
            // Write after read: the readers must finish first; an execution dependency suffices. If this
            // call also reads, the last write must become visible to it as well.
            n.needed = true;
            n.srcStages = s.readStages;
            if (readBits && s.writeStages && !isVisible(s, r.stages, readBits)) {
                n.srcStages |= s.writeStages;
                n.srcAccess = s.writeAccess;
            }
        } else if (s.writeStages) {
            if (r.noBarrierWithPreviousWriter && r.shaderWriteOnly && s.shaderWriteOnlyWriter) {
                n.skippedWriteAfterWrite = true;
            } else {
                n.needed = true;
                n.srcStages = s.writeStages;
                n.srcAccess = s.writeAccess;
            }
        }
        return n;
    }
    if (s.writeStages && !isVisible(s, r.stages, r.access)) {
        n.needed = true;
        n.srcStages = s.writeStages;
        n.srcAccess = s.writeAccess;
    }
    return n;
}

void applyAccess(AccessState& s, const AccessRequest& r, const BarrierNeed& n, bool image) {
    const bool transition = image && r.layout != s.layout;
    if (r.write) {
        if (n.skippedWriteAfterWrite) {
            // Both writers stay outstanding; the next consumer waits for both.
            s.writeStages |= r.stages;
            s.writeAccess |= r.access & kWriteAccessBits;
        } else {
            s.writeStages = r.stages;
            s.writeAccess = r.access & kWriteAccessBits;
        }
        s.readStages = 0;
        s.visibleCount = 0;
        s.shaderWriteOnlyWriter = r.shaderWriteOnly;
    } else if (transition) {
        // A transition into a read-only layout acts as a write made visible to this reader only: a reader
        // in another stage later chains from this stage (srcAccess 0).
        s.writeStages = r.stages;
        s.writeAccess = 0;
        s.readStages = r.stages;
        s.visible[0] = {r.stages, r.access};
        s.visibleCount = 1;
        s.shaderWriteOnlyWriter = false;
    } else {
        s.readStages |= r.stages;
        if (n.needed) {
            if (s.visibleCount < 4) {
                s.visible[s.visibleCount++] = {r.stages, r.access};
            } else {
                // Few distinct consumers in practice; fold the oldest into one conservative entry.
                s.visible[0].stages &= r.stages;
                s.visible[0].access &= r.access;
                s.visible[3] = {r.stages, r.access};
            }
        }
    }
    if (image) s.layout = r.layout;
}

void BarrierBatch::buffer(VkBuffer buffer, const BarrierNeed& n, const AccessRequest& r) {
    VkBufferMemoryBarrier2 b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    b.srcStageMask = n.srcStages ? n.srcStages : VK_PIPELINE_STAGE_2_NONE;
    b.srcAccessMask = n.srcAccess;
    b.dstStageMask = r.stages;
    // A pure write-after-read dependency needs no visibility operation.
    b.dstAccessMask = n.srcAccess ? r.access : 0;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = buffer;
    b.offset = 0;
    b.size = VK_WHOLE_SIZE;
    buffers_.push_back(b);
}

void BarrierBatch::image(VkImage image, VkImageAspectFlags aspect, uint32_t baseMip, uint32_t baseLayer,
                         uint32_t layerCount, const BarrierNeed& n, const AccessRequest& r) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = n.srcStages ? n.srcStages : VK_PIPELINE_STAGE_2_NONE;
    b.srcAccessMask = n.srcAccess;
    b.dstStageMask = r.stages;
    const bool transition = n.oldLayout != r.layout;
    b.dstAccessMask = (n.srcAccess || transition) ? r.access : 0;
    b.oldLayout = n.oldLayout;
    b.newLayout = r.layout;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, baseMip, 1, baseLayer, layerCount};
    images_.push_back(b);
}

void BarrierBatch::memory(VkPipelineStageFlags2 srcStages, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStages,
                          VkAccessFlags2 dstAccess) {
    VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    b.srcStageMask = srcStages;
    b.srcAccessMask = srcAccess;
    b.dstStageMask = dstStages;
    b.dstAccessMask = dstAccess;
    memory_.push_back(b);
}

uint32_t BarrierBatch::flush(VkCommandBuffer cmd) {
    if (empty()) return 0;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = static_cast<uint32_t>(memory_.size());
    dep.pMemoryBarriers = memory_.data();
    dep.bufferMemoryBarrierCount = static_cast<uint32_t>(buffers_.size());
    dep.pBufferMemoryBarriers = buffers_.data();
    dep.imageMemoryBarrierCount = static_cast<uint32_t>(images_.size());
    dep.pImageMemoryBarriers = images_.data();
    vkCmdPipelineBarrier2(cmd, &dep);
    uint32_t count = static_cast<uint32_t>(memory_.size() + buffers_.size() + images_.size());
    memory_.clear();
    buffers_.clear();
    images_.clear();
    return count;
}

}  // namespace bricklight::vulkan::detail
