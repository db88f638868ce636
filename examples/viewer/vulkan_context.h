// What bricklight-viewer owns of Vulkan below the swapchain, as an engine would: the instance (with the
// validation layer and a debug messenger when asked), the window's surface, the physical device, the one
// queue that does everything, and the logical device with the features Bricklight's embedded device uses —
// made by Bricklight's start-up (vulkan::createVulkanObjects), owned and destroyed here.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

#include "bricklight/rhi.h"
#include "bricklight/rhi_vulkan.h"

struct GLFWwindow;

namespace bricklight::viewer {

class VulkanContext {
public:
    VulkanContext() = default;
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;
    ~VulkanContext() { destroy(); }

    // validation: VK_LAYER_KHRONOS_validation (also on with env BRICKLIGHT_VK_VALIDATION=1); its messages go
    // to *errors, which must outlive the context. False + *error (one line) on failure; destroy() then
    // frees what was made.
    bool create(GLFWwindow* window, bool validation, rhi::ErrorCallback* errors, std::string* error);
    // Everything made on the device must be gone by now.
    void destroy();

    VkInstance instance() const { return objects_.instance; }
    VkSurfaceKHR surface() const { return objects_.surface; }
    VkPhysicalDevice physicalDevice() const { return objects_.physicalDevice; }
    VkDevice device() const { return objects_.device; }
    VkQueue queue() const { return objects_.queue; }
    uint32_t queueFamily() const { return objects_.queueFamilyIndex; }
    const vulkan::VulkanObjects& objects() const { return objects_; }  // what vulkan::embeddedDesc takes

    // Records into a temporary command buffer from `pool`, submits it and waits for the queue. For set-up
    // work only (layouts, font upload): it stalls.
    bool submitNow(VkCommandPool pool, void (*record)(VkCommandBuffer, void*), void* user, std::string* error) const;

private:
    vulkan::VulkanObjects objects_;
};

}  // namespace bricklight::viewer
