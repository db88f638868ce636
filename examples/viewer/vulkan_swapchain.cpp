#include "vulkan_swapchain.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>

#include "vulkan_context.h"
#include "vulkan_errors.h"

namespace bricklight::viewer {

namespace {

// The display texture already holds sRGB-encoded bytes: a UNORM swapchain shows them unchanged.
bool chooseSurfaceFormat(VkPhysicalDevice physical, VkSurfaceKHR surface, VkSurfaceFormatKHR* chosen) {
    uint32_t n = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &n, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(n);
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &n, formats.data());
    for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
        for (const VkSurfaceFormatKHR& f : formats)
            if (f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return *chosen = f, true;
    return false;
}

VkPresentModeKHR choosePresentMode(VkPhysicalDevice physical, VkSurfaceKHR surface, bool vsync) {
    if (vsync) return VK_PRESENT_MODE_FIFO_KHR;  // always supported
    uint32_t n = 0;
    vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &n, nullptr);
    std::vector<VkPresentModeKHR> modes(n);
    vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &n, modes.data());
    for (VkPresentModeKHR want : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
        for (VkPresentModeKHR m : modes)
            if (m == want) return m;
    return VK_PRESENT_MODE_FIFO_KHR;
}

}  // namespace

bool VulkanSwapchain::recreate(const VulkanContext& context, GLFWwindow* window, bool vsync, uint32_t minImageCount,
                               std::string* error) {
    device_ = context.device();
    const VkPhysicalDevice physical = context.physicalDevice();
    const VkSurfaceKHR surface = context.surface();
    VkSurfaceCapabilitiesKHR caps;
    if (VkResult r = vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, surface, &caps); r != VK_SUCCESS)
        return *error = vkFailed("vkGetPhysicalDeviceSurfaceCapabilitiesKHR", r), false;
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        return *error = "vulkan: the surface's images cannot be transfer destinations (no blit target)", false;
    // Chosen once: ImGui's pipeline is built for a render pass of this format.
    if (surfaceFormat_.format == VK_FORMAT_UNDEFINED && !chooseSurfaceFormat(physical, surface, &surfaceFormat_))
        return *error = "vulkan: the surface offers neither B8G8R8A8_UNORM nor R8G8B8A8_UNORM", false;

    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(window, &fbWidth, &fbHeight);
    extent_ = caps.currentExtent;
    if (extent_.width == UINT32_MAX) {  // the surface takes the swapchain's size
        extent_.width = std::clamp(uint32_t(fbWidth), caps.minImageExtent.width, caps.maxImageExtent.width);
        extent_.height = std::clamp(uint32_t(fbHeight), caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    uint32_t imageCount = std::max(caps.minImageCount + 1, minImageCount);
    if (caps.maxImageCount && imageCount > caps.maxImageCount) imageCount = caps.maxImageCount;

    VkSwapchainCreateInfoKHR sci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    sci.surface = surface;
    sci.minImageCount = imageCount;
    sci.imageFormat = surfaceFormat_.format;
    sci.imageColorSpace = surfaceFormat_.colorSpace;
    sci.imageExtent = extent_;
    sci.imageArrayLayers = 1;
    sci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    sci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    sci.preTransform = caps.currentTransform;
    sci.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                             ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                             : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    sci.presentMode = choosePresentMode(physical, surface, vsync);
    sci.clipped = VK_TRUE;
    sci.oldSwapchain = swapchain_;
    VkSwapchainKHR fresh = VK_NULL_HANDLE;
    VkResult r = vkCreateSwapchainKHR(device_, &sci, nullptr, &fresh);
    destroyImageObjects();
    if (swapchain_) vkDestroySwapchainKHR(device_, swapchain_, nullptr);
    swapchain_ = fresh;
    if (r != VK_SUCCESS) return *error = vkFailed("vkCreateSwapchainKHR", r), false;

    uint32_t n = 0;
    vkGetSwapchainImagesKHR(device_, swapchain_, &n, nullptr);
    images_.resize(n);
    vkGetSwapchainImagesKHR(device_, swapchain_, &n, images_.data());
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    for (VkImage image : images_) {
        VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vci.image = image;
        vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vci.format = surfaceFormat_.format;
        vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        if (VkResult rr = vkCreateImageView(device_, &vci, nullptr, &view); rr != VK_SUCCESS)
            return *error = vkFailed("vkCreateImageView (swapchain)", rr), false;
        views_.push_back(view);
        VkSemaphore semaphore = VK_NULL_HANDLE;
        if (VkResult rr = vkCreateSemaphore(device_, &semaphoreInfo, nullptr, &semaphore); rr != VK_SUCCESS)
            return *error = vkFailed("vkCreateSemaphore", rr), false;
        rendered_.push_back(semaphore);
    }
    stale_ = false;
    return true;
}

void VulkanSwapchain::destroyImageObjects() {
    for (VkImageView v : views_) vkDestroyImageView(device_, v, nullptr);
    for (VkSemaphore s : rendered_) vkDestroySemaphore(device_, s, nullptr);
    views_.clear();
    rendered_.clear();
    images_.clear();
}

void VulkanSwapchain::destroy() {
    destroyImageObjects();
    if (swapchain_) vkDestroySwapchainKHR(device_, swapchain_, nullptr);
    swapchain_ = VK_NULL_HANDLE;
}

}  // namespace bricklight::viewer
