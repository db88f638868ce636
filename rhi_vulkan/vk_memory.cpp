// Memory: one dedicated allocation per buffer/image (simple and correct; a sub-allocator can come later),
// and a per-frame upload ring of host-visible chunks that holds both the constants of each call and the
// staging copies of uploads. A chunk is reused once the frame that filled it has completed.
#include <algorithm>

#include "vk_device.h"

namespace bricklight::vulkan::detail {

namespace {
constexpr VkDeviceSize kUploadChunkSize = 1u << 20;
VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return a ? (v + a - 1) / a * a : v; }
}  // namespace

uint32_t VulkanDevice::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                                      VkMemoryPropertyFlags preferred) const {
    // First a type with every preferred property, then any type with the required ones.
    for (int pass = 0; pass < 2; ++pass) {
        VkMemoryPropertyFlags want = pass == 0 ? (required | preferred) : required;
        for (uint32_t i = 0; i < memProps_.memoryTypeCount; ++i)
            if ((typeBits & (1u << i)) && (memProps_.memoryTypes[i].propertyFlags & want) == want) return i;
    }
    return UINT32_MAX;
}

bool VulkanDevice::allocateBuffer(VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags required,
                                  VkMemoryPropertyFlags preferred, VkBuffer* buffer, VkDeviceMemory* memory,
                                  void** mapped) {
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = std::max<VkDeviceSize>(size, 4);
    bci.usage = usage;
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    if (vkCreateBuffer(device_, &bci, nullptr, buffer) != VK_SUCCESS) return false;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, *buffer, &req);
    uint32_t type = findMemoryType(req.memoryTypeBits, required, preferred);
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = type;
    if (type == UINT32_MAX || vkAllocateMemory(device_, &mai, nullptr, memory) != VK_SUCCESS) {
        vkDestroyBuffer(device_, *buffer, nullptr);
        *buffer = VK_NULL_HANDLE;
        return false;
    }
    vkBindBufferMemory(device_, *buffer, *memory, 0);
    if (mapped && vkMapMemory(device_, *memory, 0, VK_WHOLE_SIZE, 0, mapped) != VK_SUCCESS) {
        vkDestroyBuffer(device_, *buffer, nullptr);
        vkFreeMemory(device_, *memory, nullptr);
        *buffer = VK_NULL_HANDLE;
        *memory = VK_NULL_HANDLE;
        return false;
    }
    return true;
}

bool VulkanDevice::allocateImageMemory(VkImage image, VkDeviceMemory* memory) {
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device_, image, &req);
    uint32_t type = findMemoryType(req.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = type;
    if (type == UINT32_MAX || vkAllocateMemory(device_, &mai, nullptr, memory) != VK_SUCCESS) return false;
    if (vkBindImageMemory(device_, image, *memory, 0) != VK_SUCCESS) {
        vkFreeMemory(device_, *memory, nullptr);
        return false;
    }
    return true;
}

UploadAllocation VulkanDevice::allocateUpload(VkDeviceSize size, VkDeviceSize alignment) {
    FrameSlot& slot = frame();
    alignment = std::max<VkDeviceSize>(alignment, 16);
    for (UploadChunk& c : slot.chunks) {
        VkDeviceSize offset = alignUp(c.used, alignment);
        if (offset + size <= c.size) {
            c.used = offset + size;
            return {c.buffer, offset, c.mapped + offset};
        }
    }
    UploadChunk c;
    c.size = std::max(kUploadChunkSize, alignUp(size, 256));
    void* mapped = nullptr;
    if (!allocateBuffer(c.size, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, 0, &c.buffer,
                        &c.memory, &mapped))
        return {};
    c.mapped = static_cast<uint8_t*>(mapped);
    setName(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(c.buffer), "bricklight upload ring");
    c.used = size;
    slot.chunks.push_back(c);
    return {c.buffer, 0, c.mapped};
}

void VulkanDevice::releaseUploads(FrameSlot& slot) {
    // Keep the first standard-size chunks for the next use of this slot; free the oversized ones.
    std::vector<UploadChunk> kept;
    for (UploadChunk& c : slot.chunks) {
        if (c.size == kUploadChunkSize && kept.size() < 4) {
            c.used = 0;
            kept.push_back(c);
        } else {
            vkDestroyBuffer(device_, c.buffer, nullptr);
            vkFreeMemory(device_, c.memory, nullptr);
        }
    }
    slot.chunks = std::move(kept);
}

void VulkanDevice::setName(VkObjectType type, uint64_t handle, const std::string& name) const {
    if (!setObjectName_ || name.empty() || !handle) return;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name.c_str();
    setObjectName_(device_, &info);
}

}  // namespace bricklight::vulkan::detail
