#include "vk_barriers.h"

#include <algorithm>

namespace bricklight::vulkan::detail {

bool AccessRequest::merge(const AccessRequest& o) {
    if (layout != o.layout || sampled != o.sampled) return false;
    stages |= o.stages;
    access |= o.access;
    write = write || o.write;
    shaderWriteOnly = shaderWriteOnly && o.shaderWriteOnly;
    noBarrierWithPreviousWriter = noBarrierWithPreviousWriter && o.noBarrierWithPreviousWriter;
    return true;
}

namespace {

constexpr VkAccessFlags2 kShaderAccessBits = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                             VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_UNIFORM_READ_BIT;
constexpr VkPipelineStageFlags2 kShaderStageBits =
    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
    VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

bool stagesCover(VkPipelineStageFlags2 have, VkPipelineStageFlags2 want) {
    return (have & VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT) || (have & want) == want;
}
bool accessCovers(VkAccessFlags2 have, VkAccessFlags2 want) {
    if (have & VK_ACCESS_2_MEMORY_WRITE_BIT) want &= ~kWriteAccessBits;
    if (have & VK_ACCESS_2_MEMORY_READ_BIT) want &= kWriteAccessBits;
    return (have & want) == want;
}

bool isVisible(const AccessState& s, VkPipelineStageFlags2 stages, VkAccessFlags2 access) {
    for (uint8_t i = 0; i < s.visibleCount; ++i)
        if ((s.visible[i].stages & stages) == stages && (s.visible[i].access & access) == access) return true;
    return false;
}
}  // namespace

void BarrierHistory::record(const Entry& e) {
    entries_[next_] = e;
    next_ = (next_ + 1) % entries_.size();
    count_ = std::min<uint32_t>(count_ + 1, uint32_t(entries_.size()));
}

bool BarrierHistory::orders(uint64_t after, VkPipelineStageFlags2 src, VkPipelineStageFlags2 dst) const {
    for (uint32_t i = 0; i < count_; ++i) {
        const Entry& e = entries_[i];
        if (e.serial > after && stagesCover(e.srcStages, src) && stagesCover(e.dstStages, dst)) return true;
    }
    return false;
}

bool BarrierHistory::makesVisible(uint64_t after, VkPipelineStageFlags2 src, VkAccessFlags2 srcAccess,
                                  VkPipelineStageFlags2 dst, VkAccessFlags2 dstAccess) const {
    for (uint32_t i = 0; i < count_; ++i) {
        const Entry& e = entries_[i];
        if (e.serial > after && stagesCover(e.srcStages, src) && stagesCover(e.dstStages, dst) &&
            accessCovers(e.srcAccess, srcAccess) && accessCovers(e.dstAccess, dstAccess))
            return true;
    }
    return false;
}

VkAccessFlags2 accessesOfStages(VkPipelineStageFlags2 stages) {
    VkAccessFlags2 a = 0;
    if (stages & kShaderStageBits) a |= kShaderAccessBits;
    if (stages & VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT) a |= VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT;
    if (stages & VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT)
        a |= VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT;
    if (stages & VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT)
        a |= VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
    if (stages & (VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT))
        a |= VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    if (stages & VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT) a |= VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
    return a;
}

BarrierNeed computeBarrier(const AccessState& s, const AccessRequest& r, bool image, const BarrierHistory* h) {
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
            if (!(h && h->orders(s.readSerial, s.readStages, r.stages))) {
                n.needed = true;
                n.srcStages = s.readStages;
            }
            if (readBits && s.writeStages && !isVisible(s, r.stages, readBits) &&
                !(h && h->makesVisible(s.writeSerial, s.writeStages, s.writeAccess, r.stages, readBits))) {
                n.needed = true;
                n.srcStages |= s.writeStages;
                n.srcAccess = s.writeAccess;
            }
        } else if (s.writeStages) {
            if (r.noBarrierWithPreviousWriter && r.shaderWriteOnly && s.shaderWriteOnlyWriter) {
                n.skippedWriteAfterWrite = true;
            } else if (!(h && h->makesVisible(s.writeSerial, s.writeStages, s.writeAccess, r.stages, r.access))) {
                n.needed = true;
                n.srcStages = s.writeStages;
                n.srcAccess = s.writeAccess;
            }
        }
        return n;
    }
    if (s.writeStages && !isVisible(s, r.stages, r.access) &&
        !(h && h->makesVisible(s.writeSerial, s.writeStages, s.writeAccess, r.stages, r.access))) {
        n.needed = true;
        n.srcStages = s.writeStages;
        n.srcAccess = s.writeAccess;
    }
    return n;
}

void applyAccess(AccessState& s, const AccessRequest& r, const BarrierNeed& n, bool image, uint64_t serial) {
    const bool transition = image && r.layout != s.layout;
    if (r.write) {
        s.writeSerial = serial;
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
        s.writeSerial = s.readSerial = serial;
        s.readStages = r.stages;
        s.visible[0] = {r.stages, r.access};
        s.visibleCount = 1;
        s.shaderWriteOnlyWriter = false;
    } else {
        s.readStages |= r.stages;
        s.readSerial = serial;
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
