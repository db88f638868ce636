// Vulkan presentation for bricklight-viewer. The viewer owns instance, device, queue, swapchain and the
// frame's command buffer, exactly as an engine would; Bricklight runs embedded on them
// (vulkan::createEmbeddedDevice + setCommandBuffer) and the display texture is a VkImage of ours that the
// device only wraps (wrapNativeTexture), which is the integration path engines use.
//
// One frame: acquire -> [app's Bricklight calls recorded into our command buffer] -> blit the display
// image to the swapchain image -> ImGui render pass -> submit -> present -> device().endFrame().
//
// This file: the frames in flight, the display image and its wrap, the blit and the present. The Vulkan
// objects below it are in vulkan_context.h, the swapchain in vulkan_swapchain.h, ImGui's pass in
// vulkan_imgui_pass.h.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <array>
#include <cstdio>

#include "bricklight/rhi_validation.h"
#include "bricklight/rhi_vulkan.h"
#include "viewer_backend.h"
#include "vulkan_context.h"
#include "vulkan_errors.h"
#include "vulkan_imgui_pass.h"
#include "vulkan_swapchain.h"

namespace bricklight::viewer {

namespace {

using rhi::Severity;

constexpr uint32_t kFramesInFlight = 2;
// The display image stays in GENERAL between frames, so the app's storage writes need no layout transition
// per call; only the blit moves it to TRANSFER_SRC_OPTIMAL and back, twice a frame.
constexpr VkImageLayout kDisplayLayout = VK_IMAGE_LAYOUT_GENERAL;

class VulkanViewerBackend final : public ViewerBackend {
public:
    explicit VulkanViewerBackend(const BackendOptions& options) : options_(options), vsync_(options.vsync) {
        errorCallback_ = callbackOrStderr(options.errorCallback);
    }
    ~VulkanViewerBackend() override;

    bool create(std::string* error);

    const char* name() const override { return "vulkan"; }
    GLFWwindow* window() override { return window_; }
    rhi::IDevice& device() override { return api(); }
    bool beginFrame() override;
    rhi::TextureHandle displayTexture() override { return display_.handle; }
    uint32_t displayWidth() const override { return display_.width; }
    uint32_t displayHeight() const override { return display_.height; }
    void endFrame(ImDrawData* ui) override;
    void setVsync(bool on) override {
        if (on != vsync_) swapchain_.markStale();  // the present mode is fixed per swapchain
        vsync_ = on;
    }
    void waitIdle() override {
        if (device_) vkDeviceWaitIdle(context_.device());
    }

private:
    struct Display {
        VkImage image = VK_NULL_HANDLE;
        VkDeviceMemory memory = VK_NULL_HANDLE;
        rhi::TextureHandle handle;
        uint32_t width = 0, height = 0;
    };

    void report(const std::string& message) { errorCallback_(Severity::Error, message); }
    // An error after which no frame can be shown: reported once, and failed() tells the app to end.
    bool fatal(const std::string& message) {
        if (!failed_) report(message);
        failed_ = true;
        return false;
    }
    bool failed() const override { return failed_; }
    bool failed_ = false;
    bool createBricklightDevice(std::string* error);
    bool createFrameObjects(std::string* error);
    void destroyFrameObjects();
    bool recreateSwapchain(std::string* error);
    bool createDisplay(uint32_t width, uint32_t height, std::string* error);
    void destroyDisplay();
    void recordBlit(VkCommandBuffer cb, VkImage target);
    void submitAndPresent(VkCommandBuffer cb);

    BackendOptions options_;
    rhi::ErrorCallback errorCallback_;
    bool vsync_ = true;
    bool glfwReady_ = false;
    GLFWwindow* window_ = nullptr;

    VulkanContext context_;
    std::unique_ptr<rhi::IDevice> device_;
    std::unique_ptr<rhi::IDevice> validation_;  // rhi::createValidationDevice over device_ with options.validation
    // What the app and our own calls use: the validation wrapper when there is one (it must see every
    // resource the app's records name, the wrapped display texture too).
    rhi::IDevice& api() { return validation_ ? *validation_ : *device_; }

    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::array<VkCommandBuffer, kFramesInFlight> commandBuffers_{};
    std::array<VkFence, kFramesInFlight> fences_{};
    std::array<VkSemaphore, kFramesInFlight> acquired_{};
    uint32_t slot_ = 0;
    bool inFrame_ = false;

    VulkanSwapchain swapchain_;
    uint32_t imageIndex_ = 0;
    VulkanImGuiPass imgui_;

    Display display_;
};

bool VulkanViewerBackend::createBricklightDevice(std::string* error) {
    std::string deviceError;
    // The device's creation errors are also what *error should say.
    const vulkan::EmbeddedDesc desc = vulkan::embeddedDesc(context_.objects(), [this, &deviceError](Severity s, const std::string& m) {
        if (s == Severity::Error && deviceError.empty()) deviceError = m;
        errorCallback_(s, m);
    });
    device_ = vulkan::createEmbeddedDevice(desc);
    if (!device_) return *error = "vulkan: createEmbeddedDevice failed: " + deviceError, false;
    device_->setErrorCallback(errorCallback_);
    if (options_.validation) {  // and our own wrapper: every record checked against its shader's reflection
        validation_ = rhi::createValidationDevice(*device_);
        validation_->setErrorCallback(errorCallback_);
    }
    return true;
}

bool VulkanViewerBackend::createFrameObjects(std::string* error) {
    const VkDevice vkDevice = context_.device();
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = context_.queueFamily();
    if (VkResult r = vkCreateCommandPool(vkDevice, &pci, nullptr, &pool_); r != VK_SUCCESS)
        return *error = vkFailed("vkCreateCommandPool", r), false;
    VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cai.commandPool = pool_;
    cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cai.commandBufferCount = kFramesInFlight;
    if (VkResult r = vkAllocateCommandBuffers(vkDevice, &cai, commandBuffers_.data()); r != VK_SUCCESS)
        return *error = vkFailed("vkAllocateCommandBuffers", r), false;
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // the first wait on each slot returns at once
    VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    for (uint32_t i = 0; i < kFramesInFlight; ++i) {
        if (VkResult r = vkCreateFence(vkDevice, &fci, nullptr, &fences_[i]); r != VK_SUCCESS)
            return *error = vkFailed("vkCreateFence", r), false;
        if (VkResult r = vkCreateSemaphore(vkDevice, &sci, nullptr, &acquired_[i]); r != VK_SUCCESS)
            return *error = vkFailed("vkCreateSemaphore", r), false;
    }
    return true;
}

void VulkanViewerBackend::destroyFrameObjects() {
    const VkDevice vkDevice = context_.device();
    for (uint32_t i = 0; i < kFramesInFlight; ++i) {
        if (fences_[i]) vkDestroyFence(vkDevice, fences_[i], nullptr);
        if (acquired_[i]) vkDestroySemaphore(vkDevice, acquired_[i], nullptr);
    }
    if (pool_) vkDestroyCommandPool(vkDevice, pool_, nullptr);  // frees the command buffers too
    fences_ = {};
    acquired_ = {};
    commandBuffers_ = {};
    pool_ = VK_NULL_HANDLE;
}

// The ImGui pass's framebuffers name the swapchain's views, so they are rebuilt with it. The caller has
// waited for the device to be idle.
bool VulkanViewerBackend::recreateSwapchain(std::string* error) {
    imgui_.destroyFramebuffers();
    return swapchain_.recreate(context_, window_, vsync_, kFramesInFlight, error) &&
           imgui_.createFramebuffers(swapchain_, error);
}

bool VulkanViewerBackend::createDisplay(uint32_t width, uint32_t height, std::string* error) {
    const VkDevice vkDevice = context_.device();
    VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ici.imageType = VK_IMAGE_TYPE_2D;
    ici.format = VK_FORMAT_R8G8B8A8_UNORM;
    ici.extent = {width, height, 1};
    ici.mipLevels = 1;
    ici.arrayLayers = 1;
    ici.samples = VK_SAMPLE_COUNT_1_BIT;
    ici.tiling = VK_IMAGE_TILING_OPTIMAL;
    // Storage | Sampled | RenderTarget as the TextureDesc claims, plus the transfers the device uses for
    // clears and read-backs and our blit reads.
    ici.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    if (VkResult r = vkCreateImage(vkDevice, &ici, nullptr, &display_.image); r != VK_SUCCESS)
        return *error = vkFailed("vkCreateImage (display texture)", r), false;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(vkDevice, display_.image, &req);
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(context_.physicalDevice(), &mem);
    uint32_t type = UINT32_MAX;
    for (VkMemoryPropertyFlags want : {VkMemoryPropertyFlags(VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT), VkMemoryPropertyFlags(0)})
        for (uint32_t i = 0; i < mem.memoryTypeCount && type == UINT32_MAX; ++i)
            if ((req.memoryTypeBits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & want) == want) type = i;
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = type;
    if (VkResult r = vkAllocateMemory(vkDevice, &mai, nullptr, &display_.memory); r != VK_SUCCESS)
        return *error = vkFailed("vkAllocateMemory (display texture)", r), false;
    vkBindImageMemory(vkDevice, display_.image, display_.memory, 0);

    // Into the layout the wrapper is told about, before the device's first call on it.
    auto toGeneral = [](VkCommandBuffer cb, void* image) {
        VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        b.srcStageMask = VK_PIPELINE_STAGE_2_NONE;
        b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        b.newLayout = kDisplayLayout;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = *static_cast<VkImage*>(image);
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        d.imageMemoryBarrierCount = 1;
        d.pImageMemoryBarriers = &b;
        vkCmdPipelineBarrier2(cb, &d);
    };
    if (!context_.submitNow(pool_, toGeneral, &display_.image, error)) return false;

    rhi::TextureDesc desc;
    desc.format = rhi::Format::RGBA8_UNORM;
    desc.width = width;
    desc.height = height;
    desc.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled | rhi::TextureUsage::RenderTarget;
    desc.debugName = "viewer display";
    display_.handle = api().wrapNativeTexture(desc, {uint64_t(display_.image), uint64_t(kDisplayLayout)});
    if (!display_.handle) return *error = "vulkan: wrapNativeTexture refused the display image", false;
    display_.width = width;
    display_.height = height;
    return true;
}

void VulkanViewerBackend::destroyDisplay() {
    if (display_.handle) {
        api().destroy(display_.handle);
        // Frees the device's views of the image now (its deferred garbage), before the image goes.
        api().waitIdle();
    }
    if (display_.image) vkDestroyImage(context_.device(), display_.image, nullptr);
    if (display_.memory) vkFreeMemory(context_.device(), display_.memory, nullptr);
    display_ = {};
}

bool VulkanViewerBackend::create(std::string* error) {
    captureGlfwErrors();
    if (!glfwInit())
        return *error = "no display: set DISPLAY or run under Xvfb (docs/viewer.md) [GLFW: " + lastGlfwError() + "]", false;
    glfwReady_ = true;
    if (!glfwVulkanSupported()) return *error = "vulkan: GLFW found no Vulkan loader / surface support", false;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_VISIBLE, options_.hidden ? GLFW_FALSE : GLFW_TRUE);
    window_ = glfwCreateWindow(int(options_.width), int(options_.height), options_.title.c_str(), nullptr, nullptr);
    if (!window_) return *error = "vulkan: glfwCreateWindow failed: " + lastGlfwError(), false;
    if (!context_.create(window_, options_.validation, &errorCallback_, error) || !createBricklightDevice(error) ||
        !createFrameObjects(error) || !swapchain_.recreate(context_, window_, vsync_, kFramesInFlight, error))
        return false;
    // ImGui's pipeline is built for the swapchain's format, so its pass comes after the first swapchain.
    if (!imgui_.create(context_, window_, swapchain_.format(), kFramesInFlight, pool_, &errorCallback_, error) ||
        !imgui_.createFramebuffers(swapchain_, error))
        return false;
    return createDisplay(swapchain_.extent().width, swapchain_.extent().height, error);
}

// Bricklight's objects on our VkDevice go before the device's own, the device before the instance, the
// surface before the window.
VulkanViewerBackend::~VulkanViewerBackend() {
    if (context_.device()) vkDeviceWaitIdle(context_.device());
    imgui_.shutdownImGui();
    if (device_) destroyDisplay();
    validation_.reset();
    device_.reset();
    if (context_.device()) {
        imgui_.destroyFramebuffers();
        swapchain_.destroy();
        imgui_.destroy();
        destroyFrameObjects();
    }
    context_.destroy();
    if (window_) glfwDestroyWindow(window_);
    if (glfwReady_) glfwTerminate();
}

bool VulkanViewerBackend::beginFrame() {
    if (inFrame_) return report("vulkan viewer: beginFrame called twice without endFrame"), false;
    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
    if (failed_ || fbWidth <= 0 || fbHeight <= 0) return false;  // failed, or minimized: nothing can be presented

    const VkDevice vkDevice = context_.device();
    if (VkResult r = vkWaitForFences(vkDevice, 1, &fences_[slot_], VK_TRUE, UINT64_MAX); r != VK_SUCCESS)
        return fatal(vkFailed("vkWaitForFences", r));
    std::string error;
    for (int attempt = 0;; ++attempt) {
        const VkExtent2D extent = swapchain_.extent();
        if (swapchain_.stale() || uint32_t(fbWidth) != extent.width || uint32_t(fbHeight) != extent.height) {
            vkDeviceWaitIdle(vkDevice);
            if (!recreateSwapchain(&error)) return fatal(error);
        }
        if (display_.width != swapchain_.extent().width || display_.height != swapchain_.extent().height) {
            destroyDisplay();
            if (!createDisplay(swapchain_.extent().width, swapchain_.extent().height, &error)) return fatal(error);
        }
        VkResult r = vkAcquireNextImageKHR(vkDevice, swapchain_.handle(), UINT64_MAX, acquired_[slot_], VK_NULL_HANDLE,
                                           &imageIndex_);
        if (r == VK_SUCCESS) break;
        if (r == VK_SUBOPTIMAL_KHR) {  // usable now; rebuilt at the next frame
            swapchain_.markStale();
            break;
        }
        if (r != VK_ERROR_OUT_OF_DATE_KHR || attempt == 2) return fatal(vkFailed("vkAcquireNextImageKHR", r));
        swapchain_.markStale();  // acquire signalled nothing; rebuild and try again
    }
    vkResetFences(vkDevice, 1, &fences_[slot_]);  // only now: a frame that returned early submits nothing

    VkCommandBuffer cb = commandBuffers_[slot_];
    vkResetCommandBuffer(cb, 0);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cb, &bi);
    vulkan::setCommandBuffer(*device_, cb);
    inFrame_ = true;
    imgui_.newFrame();
    return true;
}

// The display image onto swapchain image `target`, which ends in TRANSFER_DST_OPTIMAL for the ImGui pass.
void VulkanViewerBackend::recordBlit(VkCommandBuffer cb, VkImage target) {
    // The device hands wrapped images back written and available (ALL_COMMANDS / MEMORY_WRITE) in
    // GENERAL; the swapchain image comes from the acquire semaphore, waited for at the blit stage.
    VkImageMemoryBarrier2 before[2] = {{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2}, {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2}};
    before[0].srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    before[0].srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    before[0].dstStageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
    before[0].dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
    before[0].oldLayout = kDisplayLayout;
    before[0].newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    before[0].image = display_.image;
    before[1].srcStageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;  // chained to the semaphore wait in submitAndPresent
    before[1].dstStageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
    before[1].dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    before[1].oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // every pixel is overwritten
    before[1].newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    before[1].image = target;
    for (VkImageMemoryBarrier2& b : before) {
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    }
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 2;
    dep.pImageMemoryBarriers = before;
    vkCmdPipelineBarrier2(cb, &dep);

    // A blit, not a copy: it converts RGBA to the swapchain's BGRA order. Same size, so no filtering.
    const VkExtent2D extent = swapchain_.extent();
    VkImageBlit region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.srcOffsets[1] = {int32_t(display_.width), int32_t(display_.height), 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstOffsets[1] = {int32_t(extent.width), int32_t(extent.height), 1};
    vkCmdBlitImage(cb, display_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, VK_FILTER_NEAREST);

    // Back to the layout the wrapper assumes. The device does not know about our read, so the app's next
    // calls (any stage) must wait for it here; made available to all, as the device's own hand-back.
    VkImageMemoryBarrier2 after = before[0];
    after.srcStageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
    after.srcAccessMask = 0;
    after.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    after.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    after.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    after.newLayout = kDisplayLayout;
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &after;
    vkCmdPipelineBarrier2(cb, &dep);
}

// Submits this slot's command buffer (after the acquire, signalling the image's "rendered" semaphore and
// the slot's fence) and presents the image once it is rendered.
void VulkanViewerBackend::submitAndPresent(VkCommandBuffer cb) {
    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait.semaphore = acquired_[slot_];
    wait.stageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
    VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signal.semaphore = swapchain_.rendered(imageIndex_);
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cbi.commandBuffer = cb;
    VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    si.waitSemaphoreInfoCount = 1;
    si.pWaitSemaphoreInfos = &wait;
    si.commandBufferInfoCount = 1;
    si.pCommandBufferInfos = &cbi;
    si.signalSemaphoreInfoCount = 1;
    si.pSignalSemaphoreInfos = &signal;
    // A failed submit signals neither the semaphore the present would wait on nor the slot's fence: present
    // nothing and end (waiting on either would hang).
    if (VkResult r = vkQueueSubmit2(context_.queue(), 1, &si, fences_[slot_]); r != VK_SUCCESS) {
        fatal(vkFailed("vkQueueSubmit2", r));
        return;
    }

    const VkSemaphore rendered = swapchain_.rendered(imageIndex_);
    const VkSwapchainKHR swapchain = swapchain_.handle();
    VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    pi.waitSemaphoreCount = 1;
    pi.pWaitSemaphores = &rendered;
    pi.swapchainCount = 1;
    pi.pSwapchains = &swapchain;
    pi.pImageIndices = &imageIndex_;
    VkResult r = vkQueuePresentKHR(context_.queue(), &pi);
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR)
        swapchain_.markStale();
    else if (r != VK_SUCCESS)
        fatal(vkFailed("vkQueuePresentKHR", r));
}

void VulkanViewerBackend::endFrame(ImDrawData* ui) {
    if (!inFrame_) return report("vulkan viewer: endFrame without a successful beginFrame");
    inFrame_ = false;
    VkCommandBuffer cb = commandBuffers_[slot_];
    recordBlit(cb, swapchain_.image(imageIndex_));
    imgui_.record(cb, imageIndex_, swapchain_.extent(), ui);
    vkEndCommandBuffer(cb);
    submitAndPresent(cb);

    // Between frames the device records into its own command buffers again (read-backs work); endFrame
    // fences its per-frame memory behind our submission.
    vulkan::setCommandBuffer(*device_, VK_NULL_HANDLE);
    api().endFrame();
    slot_ = (slot_ + 1) % kFramesInFlight;
}

}  // namespace

std::unique_ptr<ViewerBackend> ViewerBackend::createVulkan(const BackendOptions& options, std::string* error) {
    std::string ignored;
    if (!error) error = &ignored;
    auto backend = std::make_unique<VulkanViewerBackend>(options);
    if (!backend->create(error)) return nullptr;
    return backend;
}

}  // namespace bricklight::viewer
