#include "vulkan_imgui_pass.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include "vulkan_context.h"
#include "vulkan_errors.h"
#include "vulkan_swapchain.h"

namespace bricklight::viewer {

namespace {

// ImGui's Vulkan backend reports failures through a plain function pointer; route them to the live
// pass's callback (ImGui backends are process-wide, so there is at most one).
rhi::ErrorCallback* gImGuiErrorSink = nullptr;
void onImGuiVkResult(VkResult r) {
    if (r == VK_SUCCESS || !gImGuiErrorSink || !*gImGuiErrorSink) return;
    (*gImGuiErrorSink)(rhi::Severity::Error, vkFailed("ImGui_ImplVulkan", r));
}

}  // namespace

bool VulkanImGuiPass::create(const VulkanContext& context, GLFWwindow* window, VkFormat format,
                             uint32_t framesInFlight, VkCommandPool pool, rhi::ErrorCallback* errors,
                             std::string* error) {
    device_ = context.device();
    errors_ = errors;
    if (!createRenderPass(format, error)) return false;
    if (!ImGui::GetCurrentContext()) return *error = "vulkan: no ImGui context (call ImGui::CreateContext first)", false;
    // Only the font atlas takes a descriptor set; a little room for the app's own ImGui::Image textures.
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
    VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    dpi.maxSets = 16;
    dpi.poolSizeCount = 1;
    dpi.pPoolSizes = &size;
    if (VkResult r = vkCreateDescriptorPool(device_, &dpi, nullptr, &descriptorPool_); r != VK_SUCCESS)
        return *error = vkFailed("vkCreateDescriptorPool (ImGui)", r), false;

    imguiGlfw_ = ImGui_ImplGlfw_InitForVulkan(window, true);
    if (!imguiGlfw_) return *error = "vulkan: ImGui_ImplGlfw_InitForVulkan failed", false;
    gImGuiErrorSink = errors_;
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = context.instance();
    info.PhysicalDevice = context.physicalDevice();
    info.Device = device_;
    info.QueueFamily = context.queueFamily();
    info.Queue = context.queue();
    info.DescriptorPool = descriptorPool_;
    // ImGui keeps one vertex/index buffer pair per "image" and cycles through them per RenderDrawData;
    // what must not be overwritten is what a frame in flight reads, so frames in flight is the count.
    info.MinImageCount = framesInFlight;
    info.ImageCount = framesInFlight;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = onImGuiVkResult;
    imguiVulkan_ = ImGui_ImplVulkan_Init(&info, renderPass_);
    if (!imguiVulkan_) return *error = "vulkan: ImGui_ImplVulkan_Init failed", false;
    auto uploadFonts = [](VkCommandBuffer cb, void*) { ImGui_ImplVulkan_CreateFontsTexture(cb); };
    if (!context.submitNow(pool, uploadFonts, nullptr, error)) return false;
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    return true;
}

bool VulkanImGuiPass::createRenderPass(VkFormat format, std::string* error) {
    // Loads what the blit wrote (TRANSFER_DST) and hands the image to the presentation engine.
    VkAttachmentDescription attachment{};
    attachment.format = format;
    attachment.samples = VK_SAMPLE_COUNT_1_BIT;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    attachment.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkSubpassDependency afterBlit{};  // the blit's write before the load and the UI's writes
    afterBlit.srcSubpass = VK_SUBPASS_EXTERNAL;
    afterBlit.dstSubpass = 0;
    afterBlit.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    afterBlit.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    afterBlit.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    afterBlit.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo rpi{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rpi.attachmentCount = 1;
    rpi.pAttachments = &attachment;
    rpi.subpassCount = 1;
    rpi.pSubpasses = &subpass;
    rpi.dependencyCount = 1;
    rpi.pDependencies = &afterBlit;
    if (VkResult r = vkCreateRenderPass(device_, &rpi, nullptr, &renderPass_); r != VK_SUCCESS)
        return *error = vkFailed("vkCreateRenderPass", r), false;
    return true;
}

bool VulkanImGuiPass::createFramebuffers(const VulkanSwapchain& swapchain, std::string* error) {
    for (uint32_t i = 0; i < swapchain.imageCount(); ++i) {
        const VkImageView view = swapchain.view(i);
        VkFramebufferCreateInfo fbi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fbi.renderPass = renderPass_;
        fbi.attachmentCount = 1;
        fbi.pAttachments = &view;
        fbi.width = swapchain.extent().width;
        fbi.height = swapchain.extent().height;
        fbi.layers = 1;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        if (VkResult r = vkCreateFramebuffer(device_, &fbi, nullptr, &framebuffer); r != VK_SUCCESS)
            return *error = vkFailed("vkCreateFramebuffer", r), false;
        framebuffers_.push_back(framebuffer);
    }
    return true;
}

void VulkanImGuiPass::destroyFramebuffers() {
    for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(device_, f, nullptr);
    framebuffers_.clear();
}

void VulkanImGuiPass::shutdownImGui() {
    if (imguiVulkan_) ImGui_ImplVulkan_Shutdown();
    if (imguiGlfw_) ImGui_ImplGlfw_Shutdown();
    imguiVulkan_ = imguiGlfw_ = false;
    if (errors_ && gImGuiErrorSink == errors_) gImGuiErrorSink = nullptr;
}

void VulkanImGuiPass::destroy() {
    destroyFramebuffers();
    if (renderPass_) vkDestroyRenderPass(device_, renderPass_, nullptr);
    if (descriptorPool_) vkDestroyDescriptorPool(device_, descriptorPool_, nullptr);
    renderPass_ = VK_NULL_HANDLE;
    descriptorPool_ = VK_NULL_HANDLE;
}

void VulkanImGuiPass::newFrame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
}

void VulkanImGuiPass::record(VkCommandBuffer cb, uint32_t imageIndex, VkExtent2D extent, ImDrawData* ui) const {
    VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rbi.renderPass = renderPass_;
    rbi.framebuffer = framebuffers_[imageIndex];
    rbi.renderArea.extent = extent;
    vkCmdBeginRenderPass(cb, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    if (ui) ImGui_ImplVulkan_RenderDrawData(ui, cb);
    vkCmdEndRenderPass(cb);
}

}  // namespace bricklight::viewer
