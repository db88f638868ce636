// The window's swapchain: its surface format and present mode, its images and their views, and a
// "rendered" semaphore per image for the present to wait on. Recreated whole on a size or vsync change.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

struct GLFWwindow;

namespace bricklight::viewer {

class VulkanContext;

class VulkanSwapchain {
public:
    VulkanSwapchain() = default;
    VulkanSwapchain(const VulkanSwapchain&) = delete;
    VulkanSwapchain& operator=(const VulkanSwapchain&) = delete;
    ~VulkanSwapchain() { destroy(); }

    // (Re)creates the swapchain at the window's framebuffer size, with at least minImageCount images and
    // FIFO (vsync) or the fastest mode offered. The caller has waited for the device to be idle. On failure
    // the old swapchain is gone too; calling again retries.
    bool recreate(const VulkanContext& context, GLFWwindow* window, bool vsync, uint32_t minImageCount,
                  std::string* error);
    void destroy();

    // Out of date, suboptimal or another present mode wanted: rebuilt by the next frame (recreate clears it).
    void markStale() { stale_ = true; }
    bool stale() const { return stale_; }

    VkSwapchainKHR handle() const { return swapchain_; }
    VkFormat format() const { return surfaceFormat_.format; }  // chosen once, kept across recreations
    VkExtent2D extent() const { return extent_; }
    uint32_t imageCount() const { return uint32_t(images_.size()); }
    VkImage image(uint32_t index) const { return images_[index]; }
    VkImageView view(uint32_t index) const { return views_[index]; }
    // Per swapchain image, not per frame slot: a present may still wait on its semaphore until that image is
    // acquired again.
    VkSemaphore rendered(uint32_t index) const { return rendered_[index]; }

private:
    void destroyImageObjects();

    VkDevice device_ = VK_NULL_HANDLE;
    VkSurfaceFormatKHR surfaceFormat_{};
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkExtent2D extent_{};
    std::vector<VkImage> images_;
    std::vector<VkImageView> views_;
    std::vector<VkSemaphore> rendered_;
    bool stale_ = false;
};

}  // namespace bricklight::viewer
