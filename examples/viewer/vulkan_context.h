// What bricklight-viewer owns of Vulkan below the swapchain, as an engine would: the instance (with the
// validation layer and a debug messenger when asked), the window's surface, the physical device, the one
// queue that does everything, and the logical device with the features Bricklight's embedded device uses.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

#include "bricklight/rhi.h"

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

    VkInstance instance() const { return instance_; }
    VkSurfaceKHR surface() const { return surface_; }
    VkPhysicalDevice physicalDevice() const { return physical_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return family_; }
    // What an embedded Bricklight device must be told is on (vulkan::EmbeddedDesc).
    const VkPhysicalDeviceFeatures& enabledFeatures() const { return enabled_; }
    bool pushDescriptors() const { return pushDescriptors_; }
    bool debugUtils() const { return debugUtils_; }

    // Records into a temporary command buffer from `pool`, submits it and waits for the queue. For set-up
    // work only (layouts, font upload): it stalls.
    bool submitNow(VkCommandPool pool, void (*record)(VkCommandBuffer, void*), void* user, std::string* error) const;

private:
    bool createInstance(GLFWwindow* window, bool validation, rhi::ErrorCallback* errors, std::string* error);
    bool pickPhysicalDevice(std::string* error);
    bool createDevice(std::string* error);

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    bool debugUtils_ = false;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    uint32_t family_ = 0;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkPhysicalDeviceFeatures enabled_{};
    bool pushDescriptors_ = false;
};

}  // namespace bricklight::viewer
