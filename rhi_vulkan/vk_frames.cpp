// Command buffers, submission and frames in flight; deferred destruction; markers and GPU timing.
//
// Each frame slot owns a command pool, an upload ring, descriptor pools (fallback path), a timestamp query
// pool and a garbage list. Work is recorded into the slot's command buffers (or the application's, in
// embedded mode) and submitted without a fence whenever the backend must (read-backs, switching to an
// application command buffer). endFrame() submits the remainder and then an empty batch with the slot's
// fence: an empty vkQueueSubmit's fence signals once everything submitted before it has completed, which
// also covers the application's submissions in embedded mode. A slot is recycled once its fence signals.
#include <algorithm>

#include "vk_device.h"

namespace bricklight::vulkan::detail {

void VulkanDevice::createFrames() {
    for (uint32_t i = 0; i < kFramesInFlight; ++i) {
        FrameSlot& f = frames_[i];
        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
        pci.queueFamilyIndex = queueFamily_;
        vkCreateCommandPool(device_, &pci, nullptr, &f.pool);
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        vkCreateFence(device_, &fci, nullptr, &f.fence);
        if (caps_.timestamps) {
            VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
            qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
            qci.queryCount = kQueriesPerFrame;
            vkCreateQueryPool(device_, &qci, nullptr, &f.queryPool);
        }
        f.serial = i;
    }
    frames_[0].serial = 0;
}

void VulkanDevice::destroyFrames() {
    for (FrameSlot& f : frames_) {
        releaseTransient(f);
        releaseUploads(f);
        for (UploadChunk& c : f.chunks) {
            vkDestroyBuffer(device_, c.buffer, nullptr);
            vkFreeMemory(device_, c.memory, nullptr);
        }
        f.chunks.clear();
        for (VkDescriptorPool p : f.descriptorPools) vkDestroyDescriptorPool(device_, p, nullptr);
        if (f.queryPool) vkDestroyQueryPool(device_, f.queryPool, nullptr);
        if (f.fence) vkDestroyFence(device_, f.fence, nullptr);
        if (f.pool) vkDestroyCommandPool(device_, f.pool, nullptr);
    }
}

VkCommandBuffer VulkanDevice::cmd() {
    if (appCommandBuffer_) return appCommandBuffer_;
    if (recording_) return recording_;
    FrameSlot& slot = frame();
    if (slot.nextCommandBuffer == slot.commandBuffers.size()) {
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = slot.pool;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        VkCommandBuffer cb;
        vkAllocateCommandBuffers(device_, &ai, &cb);
        slot.commandBuffers.push_back(cb);
    }
    recording_ = slot.commandBuffers[slot.nextCommandBuffer++];
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(recording_, &bi);
    // Open markers continue in the new command buffer.
    if (debugUtils_)
        for (OpenMarker& m : markers_) {
            VkDebugUtilsLabelEXT l{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
            l.pLabelName = m.label.c_str();
            beginLabel_(recording_, &l);
            m.labelCommandBuffer = recording_;
        }
    return recording_;
}

void VulkanDevice::flushInternal() {
    if (!recording_) return;
    if (debugUtils_)
        for (auto it = markers_.rbegin(); it != markers_.rend(); ++it)
            if (it->labelCommandBuffer == recording_) {
                endLabel_(recording_);
                it->labelCommandBuffer = VK_NULL_HANDLE;
            }
    vkEndCommandBuffer(recording_);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &recording_;
    vkQueueSubmit(queue_, 1, &si, VK_NULL_HANDLE);
    recording_ = VK_NULL_HANDLE;
}

void VulkanDevice::setAppCommandBuffer(VkCommandBuffer commandBuffer) {
    // Work recorded so far goes to the queue first, so it runs before the application's command buffer.
    flushInternal();
    appCommandBuffer_ = commandBuffer;
}

bool VulkanDevice::waitForGpu() {
    flushInternal();
    if (vkQueueSubmit(queue_, 0, nullptr, syncFence_) != VK_SUCCESS) return fail("vkQueueSubmit failed");
    VkResult r = vkWaitForFences(device_, 1, &syncFence_, VK_TRUE, UINT64_MAX);
    vkResetFences(device_, 1, &syncFence_);
    if (r != VK_SUCCESS) return fail("vkWaitForFences failed (device lost?)");
    waitCount_++;
    for (FrameSlot& f : frames_)
        if (f.pending) {
            vkWaitForFences(device_, 1, &f.fence, VK_TRUE, UINT64_MAX);
            recycle(f, true);
        }
    // The current frame's transient objects may still be referenced by an application command buffer
    // that has not been submitted yet; otherwise everything they were used for has completed.
    if (!appCommandBuffer_) releaseTransient(frame());
    return true;
}

void VulkanDevice::releaseTransient(FrameSlot& slot) {
    if (slot.pool) vkResetCommandPool(device_, slot.pool, 0);
    slot.nextCommandBuffer = 0;
    for (UploadChunk& c : slot.chunks) c.used = 0;
    releaseUploads(slot);
    for (VkDescriptorPool p : slot.descriptorPools) vkResetDescriptorPool(device_, p, 0);
    slot.currentDescriptorPool = 0;
    auto garbage = std::move(slot.garbage);
    slot.garbage.clear();
    for (auto& fn : garbage) fn();
}

void VulkanDevice::recycle(FrameSlot& slot, bool harvestTimings) {
    if (harvestTimings && !slot.timed.empty()) {
        const double period = props_.limits.timestampPeriod;
        const uint64_t mask = timestampValidBits_ >= 64 ? ~0ull : ((1ull << timestampValidBits_) - 1);
        for (const auto& t : slot.timed) {
            uint64_t begin = 0, end = 0;
            if (vkGetQueryPoolResults(device_, slot.queryPool, t.beginQuery, 1, sizeof(begin), &begin, sizeof(begin),
                                      VK_QUERY_RESULT_64_BIT) != VK_SUCCESS ||
                vkGetQueryPoolResults(device_, slot.queryPool, t.endQuery, 1, sizeof(end), &end, sizeof(end),
                                      VK_QUERY_RESULT_64_BIT) != VK_SUCCESS)
                continue;
            const uint64_t ticks = ((end & mask) - (begin & mask)) & mask;
            finishedTimings_.push_back({t.label, double(ticks) * period / 1e6, slot.serial});
        }
    }
    if (harvestTimings) {
        slot.timed.clear();
        slot.queriesUsed = 0;
    }
    releaseTransient(slot);
    if (slot.pending) {
        completedSerial_ = std::max(completedSerial_, int64_t(slot.serial));
        vkResetFences(device_, 1, &slot.fence);
    }
    slot.pending = false;
}

void VulkanDevice::deferDestroy(std::function<void()> fn) { frame().garbage.push_back(std::move(fn)); }

void VulkanDevice::endFrame() {
    flushInternal();
    FrameSlot& done = frame();
    if (vkQueueSubmit(queue_, 0, nullptr, done.fence) != VK_SUCCESS) {
        fail("endFrame: vkQueueSubmit failed");
        return;
    }
    done.pending = true;
    frameSerial_++;
    currentFrame_ = static_cast<uint32_t>(frameSerial_ % kFramesInFlight);
    FrameSlot& next = frame();
    if (next.pending) {
        // Too many frames in flight: this is the only place the backend waits in a normal frame.
        vkWaitForFences(device_, 1, &next.fence, VK_TRUE, UINT64_MAX);
        recycle(next, true);
    }
    next.serial = frameSerial_;
}

void VulkanDevice::waitIdle() { waitForGpu(); }

// ---------------------------------------------------------------------------------------------------
// Markers and timing
// ---------------------------------------------------------------------------------------------------

void VulkanDevice::beginMarker(const char* label) {
    std::string name = label ? label : "";
    // Bounded: each open marker keeps its whole path, and every new command buffer re-opens them all.
    if (markers_.size() + refusedMarkers_ >= rhi::kMaxMarkerDepth) {
        if (refusedMarkers_++ == 0)
            reporter_->report(rhi::Severity::Error, "beginMarker '" + name.substr(0, 64) + "': more than kMaxMarkerDepth " +
                                                        std::to_string(rhi::kMaxMarkerDepth) + " markers open; refused");
        return;
    }
    OpenMarker m;
    m.label = markers_.empty() ? name : markers_.back().label + "/" + name;
    m.frame = frameSerial_;
    VkCommandBuffer c = cmd();  // before pushing: cmd() re-opens the labels of the open markers
    if (debugUtils_) {
        VkDebugUtilsLabelEXT l{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
        l.pLabelName = m.label.c_str();
        beginLabel_(c, &l);
        m.labelCommandBuffer = c;
    }
    FrameSlot& slot = frame();
    if (timingEnabled_ && slot.queryPool && markers_.size() < timingDepth_) {
        if (slot.queriesUsed + 2 <= kQueriesPerFrame) {
            if (slot.queriesUsed == 0) vkCmdResetQueryPool(c, slot.queryPool, 0, kQueriesPerFrame);
            m.beginQuery = slot.queriesUsed++;
            slot.queriesUsed++;  // reserve the end query so that a pair never straddles the pool's end
            vkCmdWriteTimestamp2(c, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.queryPool, uint32_t(m.beginQuery));
        } else if (!queryOverflowReported_) {
            queryOverflowReported_ = true;
            warn("beginMarker '" + name + "': more than " + std::to_string(kQueriesPerFrame / 2) +
                 " timed markers in one frame; the rest are not timed");
        }
    }
    markers_.push_back(std::move(m));
}

void VulkanDevice::endMarker() {
    if (refusedMarkers_) {
        --refusedMarkers_;
        return;
    }
    if (markers_.empty()) {
        warn("endMarker: no marker is open");
        return;
    }
    VkCommandBuffer c = cmd();
    OpenMarker& m = markers_.back();
    FrameSlot& slot = frame();
    if (m.beginQuery >= 0 && m.frame == frameSerial_) {
        const uint32_t endQuery = uint32_t(m.beginQuery) + 1;
        vkCmdWriteTimestamp2(c, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.queryPool, endQuery);
        slot.timed.push_back({m.label, uint32_t(m.beginQuery), endQuery});
    }
    if (debugUtils_ && m.labelCommandBuffer == c) endLabel_(c);
    markers_.pop_back();
}

std::vector<rhi::MarkerTiming> VulkanDevice::takeTimings() {
    for (FrameSlot& f : frames_)
        if (f.pending && vkGetFenceStatus(device_, f.fence) == VK_SUCCESS) recycle(f, true);
    std::vector<rhi::MarkerTiming> out = std::move(finishedTimings_);
    finishedTimings_.clear();
    return out;
}

}  // namespace bricklight::vulkan::detail
