// Image views, cached per texture by (format, view type, usage, mip range, layer range). The usage is part
// of the key because every view declares (VkImageViewUsageCreateInfo) only the usage it is made for: an
// sRGB image created with STORAGE for its UNORM views must not offer STORAGE through an sRGB view.
#include "vk_device.h"

namespace bricklight::vulkan::detail {

VkImageView VulkanDevice::getView(Texture& t, const ViewKey& key) {
    for (auto& [k, view] : t.views)
        if (k == key) return view;
    VkImageViewUsageCreateInfo usage{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
    usage.usage = key.usage;
    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.pNext = &usage;
    vci.image = t.image;
    vci.viewType = key.type;
    vci.format = key.format;
    vci.subresourceRange = {t.aspect, key.baseMip, key.mipCount, key.baseLayer, key.layerCount};
    VkImageView view = VK_NULL_HANDLE;
    if (vkCreateImageView(device_, &vci, nullptr, &view) != VK_SUCCESS) return VK_NULL_HANDLE;
    if (!t.desc.debugName.empty())
        setName(VK_OBJECT_TYPE_IMAGE_VIEW, reinterpret_cast<uint64_t>(view),
                t.desc.debugName + " view mip " + std::to_string(key.baseMip) + " layer " +
                    std::to_string(key.baseLayer));
    t.views.emplace_back(key, view);
    return view;
}

}  // namespace bricklight::vulkan::detail
