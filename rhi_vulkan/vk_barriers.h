// Hazard tracking from declared access. Each buffer (whole) and each texture subresource (mip x layer)
// keeps an AccessState; before a call, computeBarrier() says which barrier (if any) the new access needs
// and applyAccess() records the access. The rules (docs/backend_vulkan.md "Barriers"):
//   read after write  -> memory barrier from the writer, unless the write is already visible to this
//                        stage+access (an earlier barrier made it so)
//   write after write -> memory barrier (skipped under NoBarrierWithPreviousWriter when both calls only
//                        write from shaders)
//   write after read  -> execution dependency on the readers only
//   layout change     -> image barrier from the writer and all readers since
//   read after read   -> nothing
// A hazard that an earlier barrier already ordered needs nothing more (BarrierHistory): a
// vkCmdPipelineBarrier2 orders *every* earlier command's work in its source stages before every later
// command's work in its destination stages, whatever resources it names, so a write-after-read against
// readers from several passes ago is usually covered. The backend records all non-transition dependencies
// of a call as one global memory barrier over everything outstanding (vk_tracking.cpp), which makes such
// reuse common: passes without a hazard of their own then run between the same two barriers and overlap.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <vector>

namespace bricklight::vulkan::detail {

constexpr VkAccessFlags2 kWriteAccessBits =
    VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_WRITE_BIT |
    VK_ACCESS_2_MEMORY_WRITE_BIT;

struct AccessState {
    VkPipelineStageFlags2 writeStages = 0;  // last write (or the stage a layout transition was made for)
    VkAccessFlags2 writeAccess = 0;         // 0 after a transition into a read-only layout
    VkPipelineStageFlags2 readStages = 0;   // readers since the last write
    struct Visible {
        VkPipelineStageFlags2 stages;
        VkAccessFlags2 access;
    };
    // (stage, access) pairs the last write has already been made visible to by an emitted barrier.
    Visible visible[4] = {};
    uint8_t visibleCount = 0;
    bool shaderWriteOnlyWriter = false;  // the last writer only wrote (Write/Atomic) from a shader
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    uint64_t writeSerial = 0;  // the call that made the last write (or transition)
    uint64_t readSerial = 0;   // the latest call among the readers since
};

// Everything one call does to one buffer or subresource, merged over its bindings.
struct AccessRequest {
    VkPipelineStageFlags2 stages = 0;
    VkAccessFlags2 access = 0;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // images only
    bool write = false;
    bool sampled = false;         // a sampled-texture binding (never merged with a storage one)
    bool shaderWriteOnly = true;  // every access of the call is a shader Write/Atomic
    bool noBarrierWithPreviousWriter = false;

    // Merges another access of the same call; returns false when the two need different layouts.
    bool merge(const AccessRequest& other);
};

struct BarrierNeed {
    bool needed = false;
    bool skippedWriteAfterWrite = false;
    VkPipelineStageFlags2 srcStages = 0;
    VkAccessFlags2 srcAccess = 0;
    VkImageLayout oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    bool operator==(const BarrierNeed& o) const {
        return needed == o.needed && skippedWriteAfterWrite == o.skippedWriteAfterWrite && srcStages == o.srcStages &&
               srcAccess == o.srcAccess && oldLayout == o.oldLayout;
    }
};

// The barriers recorded lately, by the serial of the call they were recorded for (each call's barrier
// precedes its own command, so it orders accesses of calls with a smaller serial only). A bounded ring:
// forgetting old entries only costs barriers, never correctness.
class BarrierHistory {
public:
    struct Entry {
        uint64_t serial;
        VkPipelineStageFlags2 srcStages, dstStages;
        VkAccessFlags2 srcAccess, dstAccess;  // of the global memory barrier (0: execution only)
    };
    void record(const Entry& entry);
    // True when a barrier recorded after call `after` made work in `srcStages` finish before `dstStages`.
    bool orders(uint64_t after, VkPipelineStageFlags2 srcStages, VkPipelineStageFlags2 dstStages) const;
    // The same, and it also made writes of `srcAccess` visible to `dstAccess`.
    bool makesVisible(uint64_t after, VkPipelineStageFlags2 srcStages, VkAccessFlags2 srcAccess,
                      VkPipelineStageFlags2 dstStages, VkAccessFlags2 dstAccess) const;

private:
    std::array<Entry, 32> entries_{};
    uint32_t count_ = 0, next_ = 0;
};

// What `request` needs against `state`. `history` may be null: no reuse of earlier barriers (objects the
// application wraps, which it may write between our calls, or reuse turned off).
BarrierNeed computeBarrier(const AccessState& state, const AccessRequest& request, bool image,
                           const BarrierHistory* history);
// Records the access made by call `serial` (after its barrier, if any).
void applyAccess(AccessState& state, const AccessRequest& request, const BarrierNeed& need, bool image,
                 uint64_t serial);

// The access types a global barrier into `stages` makes visible (every kind this backend declares there).
VkAccessFlags2 accessesOfStages(VkPipelineStageFlags2 stages);

// The barriers of one call, recorded with a single vkCmdPipelineBarrier2.
class BarrierBatch {
public:
    void buffer(VkBuffer buffer, const BarrierNeed& need, const AccessRequest& request);
    void image(VkImage image, VkImageAspectFlags aspect, uint32_t baseMip, uint32_t baseLayer, uint32_t layerCount,
               const BarrierNeed& need, const AccessRequest& request);
    void memory(VkPipelineStageFlags2 srcStages, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStages,
                VkAccessFlags2 dstAccess);
    // Records the batch (if any) and returns how many barrier structures it held.
    uint32_t flush(VkCommandBuffer cmd);
    bool empty() const { return buffers_.empty() && images_.empty() && memory_.empty(); }

private:
    std::vector<VkBufferMemoryBarrier2> buffers_;
    std::vector<VkImageMemoryBarrier2> images_;
    std::vector<VkMemoryBarrier2> memory_;
};

}  // namespace bricklight::vulkan::detail
