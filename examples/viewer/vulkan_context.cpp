#include "vulkan_context.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <memory>
#include <optional>

#include "vulkan_errors.h"

namespace bricklight::viewer {

bool VulkanContext::create(GLFWwindow* window, bool validation, rhi::ErrorCallback* errors, std::string* error) {
    uint32_t glfwCount = 0;
    const char** glfwExtensions = glfwGetRequiredInstanceExtensions(&glfwCount);
    if (!glfwExtensions)
        return *error = "vulkan: no window-system surface extensions (VK_KHR_surface + xlib/xcb/wayland); is a Vulkan "
                        "driver installed?" + (lastGlfwError().empty() ? "" : " " + lastGlfwError()),
               false;
    vulkan::StartupDesc sd;
    sd.applicationName = "bricklight-viewer";
    sd.enableValidation = validation;
    sd.instanceExtensions.assign(glfwExtensions, glfwExtensions + glfwCount);
    sd.deviceExtensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
    sd.createSurface = [window](VkInstance instance, VkSurfaceKHR* surface) { return glfwCreateWindowSurface(instance, window, nullptr, surface); };
    // Failures are also what *error says; everything (validation messages too) goes on to *errors.
    // (The messenger keeps the callback: the failure text lives as long.)
    auto failure = std::make_shared<std::string>();
    sd.errorCallback = [errors, failure](rhi::Severity s, const std::string& m) {
        if (s == rhi::Severity::Error && failure->empty()) *failure = m;
        if (*errors) (*errors)(s, m);
    };
    std::optional<vulkan::VulkanObjects> objects = vulkan::createVulkanObjects(sd);
    if (!objects) return *error = "vulkan: " + *failure + (lastGlfwError().empty() ? "" : " " + lastGlfwError()), false;
    objects_ = std::move(*objects);
    return true;
}

void VulkanContext::destroy() { vulkan::destroyVulkanObjects(objects_); }

bool VulkanContext::submitNow(VkCommandPool pool, void (*record)(VkCommandBuffer, void*), void* user,
                              std::string* error) const {
    VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cai.commandPool = pool;
    cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cai.commandBufferCount = 1;
    VkCommandBuffer cb = VK_NULL_HANDLE;
    if (VkResult r = vkAllocateCommandBuffers(objects_.device, &cai, &cb); r != VK_SUCCESS)
        return *error = vkFailed("vkAllocateCommandBuffers", r), false;
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cb, &bi);
    record(cb, user);
    vkEndCommandBuffer(cb);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    VkResult r = vkQueueSubmit(objects_.queue, 1, &si, VK_NULL_HANDLE);
    if (r == VK_SUCCESS) r = vkQueueWaitIdle(objects_.queue);
    vkFreeCommandBuffers(objects_.device, pool, 1, &cb);
    if (r != VK_SUCCESS) return *error = vkFailed("vkQueueSubmit (set-up)", r), false;
    return true;
}

}  // namespace bricklight::viewer
