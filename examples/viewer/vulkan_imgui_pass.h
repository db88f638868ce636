// Dear ImGui drawn over the swapchain image: a render pass that loads the picture the viewer blitted there
// and hands the image to the presentation engine, a framebuffer per swapchain image, and ImGui's GLFW and
// Vulkan backends with their descriptor pool. ImGui's backends are process-wide: one pass at a time.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

#include "bricklight/rhi.h"

struct GLFWwindow;
struct ImDrawData;

namespace bricklight::viewer {

class VulkanContext;
class VulkanSwapchain;

class VulkanImGuiPass {
public:
    VulkanImGuiPass() = default;
    VulkanImGuiPass(const VulkanImGuiPass&) = delete;
    VulkanImGuiPass& operator=(const VulkanImGuiPass&) = delete;
    ~VulkanImGuiPass() {
        shutdownImGui();
        destroy();
    }

    // The render pass for swapchain images of `format`, and ImGui's backends on it (the app's ImGui context
    // must exist). The font atlas is uploaded at once through `pool`. ImGui's Vulkan failures go to *errors,
    // which must outlive the pass. framesInFlight: how many frames may read ImGui's buffers at a time.
    bool create(const VulkanContext& context, GLFWwindow* window, VkFormat format, uint32_t framesInFlight,
                VkCommandPool pool, rhi::ErrorCallback* errors, std::string* error);
    // One framebuffer per image of the current swapchain; rebuilt with it (destroy first, then recreate).
    bool createFramebuffers(const VulkanSwapchain& swapchain, std::string* error);
    void destroyFramebuffers();
    // ImGui's own Vulkan objects go here, while the device still works; destroy() frees ours.
    void shutdownImGui();
    void destroy();

    // The platform and renderer halves of ImGui's frame; the app calls ImGui::NewFrame() after.
    void newFrame();
    // The pass over swapchain image `imageIndex`, which the blit left in TRANSFER_DST_OPTIMAL (loaded, not
    // cleared) and which ends in PRESENT_SRC_KHR. `ui` may be null: the pass then only changes the layout.
    void record(VkCommandBuffer cb, uint32_t imageIndex, VkExtent2D extent, ImDrawData* ui) const;

private:
    bool createRenderPass(VkFormat format, std::string* error);

    VkDevice device_ = VK_NULL_HANDLE;
    VkRenderPass renderPass_ = VK_NULL_HANDLE;
    std::vector<VkFramebuffer> framebuffers_;
    VkDescriptorPool descriptorPool_ = VK_NULL_HANDLE;
    bool imguiGlfw_ = false, imguiVulkan_ = false;
    rhi::ErrorCallback* errors_ = nullptr;
};

}  // namespace bricklight::viewer
