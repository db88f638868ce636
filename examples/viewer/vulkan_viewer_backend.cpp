// Vulkan presentation for bricklight-viewer. The viewer owns instance, device, queue, swapchain and the
// frame's command buffer, exactly as an engine would; Bricklight runs embedded on them
// (vulkan::createEmbeddedDevice + setCommandBuffer) and the display texture is a VkImage of ours that the
// device only wraps (wrapNativeTexture), which is the integration path engines use.
//
// One frame: acquire -> [app's Bricklight calls recorded into our command buffer] -> blit the display
// image to the swapchain image -> ImGui render pass -> submit -> present -> device().endFrame().
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "bricklight/rhi_vulkan.h"
#include "bricklight/rhi_validation.h"
#include "viewer_backend.h"

namespace bricklight::viewer {

namespace {

using rhi::Severity;

constexpr uint32_t kFramesInFlight = 2;
// The display image stays in GENERAL between frames, so the app's storage writes need no layout transition
// per call; only the blit moves it to TRANSFER_SRC_OPTIMAL and back, twice a frame.
constexpr VkImageLayout kDisplayLayout = VK_IMAGE_LAYOUT_GENERAL;

const char* resultName(VkResult r) {
    switch (r) {
#define BL_CASE(x) \
    case x: return #x;
        BL_CASE(VK_SUCCESS)
        BL_CASE(VK_NOT_READY)
        BL_CASE(VK_TIMEOUT)
        BL_CASE(VK_SUBOPTIMAL_KHR)
        BL_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        BL_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        BL_CASE(VK_ERROR_INITIALIZATION_FAILED)
        BL_CASE(VK_ERROR_DEVICE_LOST)
        BL_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        BL_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        BL_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        BL_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        BL_CASE(VK_ERROR_SURFACE_LOST_KHR)
        BL_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
        BL_CASE(VK_ERROR_OUT_OF_DATE_KHR)
        BL_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
#undef BL_CASE
        default: return "VkResult error";
    }
}

std::string vkFailed(const char* call, VkResult r) {
    return std::string("vulkan: ") + call + " failed (" + resultName(r) + ")";
}

// GLFW reports why a call failed only through its error callback; keep the last message for ours.
std::string& lastGlfwError() {
    static std::string message;
    return message;
}
void onGlfwError(int, const char* description) { lastGlfwError() = description ? description : ""; }

bool hasLayer(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    for (const VkLayerProperties& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

bool hasInstanceExtension(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> extensions(n);
    vkEnumerateInstanceExtensionProperties(nullptr, &n, extensions.data());
    for (const VkExtensionProperties& e : extensions)
        if (std::strcmp(e.extensionName, name) == 0) return true;
    return false;
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> extensions(n);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &n, extensions.data());
    for (const VkExtensionProperties& e : extensions)
        if (std::strcmp(e.extensionName, name) == 0) return true;
    return false;
}

// One queue does everything: Bricklight needs graphics + compute in one stream, and presenting from the
// same queue needs no ownership transfer of the swapchain image.
int64_t universalFamily(VkPhysicalDevice device, VkSurfaceKHR surface) {
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &n, families.data());
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (uint32_t i = 0; i < n; ++i) {
        VkBool32 present = VK_FALSE;
        vkGetPhysicalDeviceSurfaceSupportKHR(device, i, surface, &present);
        if ((families[i].queueFlags & need) == need && present) return i;
    }
    return -1;
}

// ImGui's Vulkan backend reports failures through a plain function pointer; route them to the live
// backend's callback (ImGui backends are process-wide, so there is at most one).
rhi::ErrorCallback* gImGuiErrorSink = nullptr;
void onImGuiVkResult(VkResult r) {
    if (r == VK_SUCCESS || !gImGuiErrorSink || !*gImGuiErrorSink) return;
    (*gImGuiErrorSink)(Severity::Error, vkFailed("ImGui_ImplVulkan", r));
}

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* callback = static_cast<rhi::ErrorCallback*>(user);
    const std::string message = std::string("vulkan validation: ") + (data && data->pMessage ? data->pMessage : "");
    if (*callback) (*callback)(Severity::Error, message);
    return VK_FALSE;
}

class VulkanViewerBackend final : public ViewerBackend {
public:
    explicit VulkanViewerBackend(const BackendOptions& options) : options_(options), vsync_(options.vsync) {
        // Stored in the object (its address is handed to the messenger and ImGui), never empty.
        errorCallback_ = options.errorCallback;
        if (!errorCallback_)
            errorCallback_ = [](Severity, const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); };
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
        if (on != vsync_) swapchainStale_ = true;  // the present mode is fixed per swapchain
        vsync_ = on;
    }
    void waitIdle() override {
        if (device_) vkDeviceWaitIdle(vkDevice_);
    }

private:
    struct Display {
        VkImage image = VK_NULL_HANDLE;
        VkDeviceMemory memory = VK_NULL_HANDLE;
        rhi::TextureHandle handle;
        uint32_t width = 0, height = 0;
    };

    void report(const std::string& message) { errorCallback_(Severity::Error, message); }
    bool createInstance(std::string* error);
    bool pickDevice(std::string* error);
    bool createDevice(std::string* error);
    bool createFrameObjects(std::string* error);
    bool createSwapchain(std::string* error);
    void destroySwapchainViews();
    bool createDisplay(uint32_t width, uint32_t height, std::string* error);
    void destroyDisplay();
    bool initImGui(std::string* error);
    bool submitNow(void (*record)(VkCommandBuffer, void*), void* user, std::string* error);
    VkPresentModeKHR choosePresentMode() const;

    BackendOptions options_;
    rhi::ErrorCallback errorCallback_;
    bool vsync_ = true;
    bool glfwReady_ = false;
    GLFWwindow* window_ = nullptr;
    bool imguiGlfw_ = false, imguiVulkan_ = false;

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    bool debugUtils_ = false;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    uint32_t family_ = 0;
    VkDevice vkDevice_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkPhysicalDeviceFeatures enabled_{};
    bool pushDescriptors_ = false;
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

    VkSurfaceFormatKHR surfaceFormat_{};
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkExtent2D extent_{};
    std::vector<VkImage> images_;
    std::vector<VkImageView> views_;
    std::vector<VkFramebuffer> framebuffers_;
    // Per swapchain image, not per frame slot: a present may still wait on its semaphore until that
    // image is acquired again.
    std::vector<VkSemaphore> rendered_;
    uint32_t imageIndex_ = 0;
    bool swapchainStale_ = false;
    VkRenderPass renderPass_ = VK_NULL_HANDLE;  // ImGui's pass: loads the blitted picture, ends in PRESENT_SRC
    VkDescriptorPool imguiPool_ = VK_NULL_HANDLE;

    Display display_;
};

bool VulkanViewerBackend::createInstance(std::string* error) {
    uint32_t loaderVersion = VK_API_VERSION_1_0;
    vkEnumerateInstanceVersion(&loaderVersion);
    if (loaderVersion < VK_API_VERSION_1_3) return *error = "vulkan: the Vulkan loader is older than 1.3", false;

    uint32_t glfwCount = 0;
    const char** glfwExtensions = glfwGetRequiredInstanceExtensions(&glfwCount);
    if (!glfwExtensions)
        return *error = "vulkan: no window-system surface extensions (VK_KHR_surface + xlib/xcb/wayland); is a Vulkan "
                        "driver installed?" + (lastGlfwError().empty() ? "" : " " + lastGlfwError()),
               false;
    std::vector<const char*> extensions(glfwExtensions, glfwExtensions + glfwCount);
    std::vector<const char*> layers;
    const char* env = std::getenv("BRICKLIGHT_VK_VALIDATION");
    const bool validation = options_.validation || (env && std::strcmp(env, "1") == 0);
    if (validation) {
        if (hasLayer("VK_LAYER_KHRONOS_validation"))
            layers.push_back("VK_LAYER_KHRONOS_validation");
        else
            errorCallback_(Severity::Warning, "vulkan: VK_LAYER_KHRONOS_validation is not installed; validation is off");
    }
    debugUtils_ = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (debugUtils_) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = onValidationMessage;
    messengerInfo.pUserData = &errorCallback_;
    const bool messenger = !layers.empty() && debugUtils_;

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "bricklight-viewer";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ici.pNext = messenger ? &messengerInfo : nullptr;  // chained: instance creation is checked too
    ici.pApplicationInfo = &app;
    ici.enabledLayerCount = uint32_t(layers.size());
    ici.ppEnabledLayerNames = layers.data();
    ici.enabledExtensionCount = uint32_t(extensions.size());
    ici.ppEnabledExtensionNames = extensions.data();
    if (VkResult r = vkCreateInstance(&ici, nullptr, &instance_); r != VK_SUCCESS)
        return *error = vkFailed("vkCreateInstance", r), false;
    if (messenger) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!create || create(instance_, &messengerInfo, nullptr, &messenger_) != VK_SUCCESS)
            return *error = "vulkan: cannot create the debug messenger", false;
    }
    if (VkResult r = glfwCreateWindowSurface(instance_, window_, nullptr, &surface_); r != VK_SUCCESS)
        return *error = vkFailed("glfwCreateWindowSurface", r) + ": " + lastGlfwError(), false;
    return true;
}

bool VulkanViewerBackend::pickDevice(std::string* error) {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> candidates(count);
    vkEnumeratePhysicalDevices(instance_, &count, candidates.data());
    int bestScore = -1;
    for (VkPhysicalDevice pd : candidates) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd, &p);
        VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        f2.pNext = &f13;
        vkGetPhysicalDeviceFeatures2(pd, &f2);
        if (p.apiVersion < VK_API_VERSION_1_3 || !f13.synchronization2 || !f13.dynamicRendering ||
            !hasDeviceExtension(pd, VK_KHR_SWAPCHAIN_EXTENSION_NAME) || universalFamily(pd, surface_) < 0)
            continue;
        const int score = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU     ? 3
                          : p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ? 2
                                                                                   : 1;
        if (score > bestScore) bestScore = score, physical_ = pd;
    }
    if (!physical_)
        return *error = "vulkan: no Vulkan 1.3 device with synchronization2, dynamicRendering, VK_KHR_swapchain "
                        "and a graphics+compute queue that can present to the window",
               false;
    family_ = uint32_t(universalFamily(physical_, surface_));
    return true;
}

bool VulkanViewerBackend::createDevice(std::string* error) {
    // The optional features the standalone device enables (rhi_vulkan/vk_setup.cpp), so that the embedded
    // one can use the same shader paths; EmbeddedDesc tells it which are on.
    VkPhysicalDeviceFeatures supported;
    vkGetPhysicalDeviceFeatures(physical_, &supported);
    enabled_.geometryShader = supported.geometryShader;
    enabled_.depthClamp = supported.depthClamp;
    enabled_.samplerAnisotropy = supported.samplerAnisotropy;
    enabled_.independentBlend = supported.independentBlend;
    enabled_.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
    enabled_.vertexPipelineStoresAndAtomics = supported.vertexPipelineStoresAndAtomics;
    enabled_.shaderStorageImageExtendedFormats = supported.shaderStorageImageExtendedFormats;
    enabled_.shaderStorageImageReadWithoutFormat = supported.shaderStorageImageReadWithoutFormat;
    enabled_.shaderStorageImageWriteWithoutFormat = supported.shaderStorageImageWriteWithoutFormat;
    enabled_.largePoints = supported.largePoints;
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.synchronization2 = VK_TRUE;
    f13.dynamicRendering = VK_TRUE;
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.pNext = &f13;
    f2.features = enabled_;
    std::vector<const char*> extensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
    pushDescriptors_ = hasDeviceExtension(physical_, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    if (pushDescriptors_) extensions.push_back(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = family_;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.pNext = &f2;
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = uint32_t(extensions.size());
    dci.ppEnabledExtensionNames = extensions.data();
    if (VkResult r = vkCreateDevice(physical_, &dci, nullptr, &vkDevice_); r != VK_SUCCESS)
        return *error = vkFailed("vkCreateDevice", r), false;
    vkGetDeviceQueue(vkDevice_, family_, 0, &queue_);

    std::string deviceError;
    vulkan::EmbeddedDesc desc;
    desc.instance = instance_;
    desc.physicalDevice = physical_;
    desc.device = vkDevice_;
    desc.queue = queue_;
    desc.queueFamilyIndex = family_;
    desc.enabledFeatures = &enabled_;
    desc.pushDescriptorEnabled = pushDescriptors_;
    desc.debugUtilsEnabled = debugUtils_;
    // The device's creation errors are also what *error should say.
    desc.errorCallback = [this, &deviceError](Severity s, const std::string& m) {
        if (s == Severity::Error && deviceError.empty()) deviceError = m;
        errorCallback_(s, m);
    };
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
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = family_;
    if (VkResult r = vkCreateCommandPool(vkDevice_, &pci, nullptr, &pool_); r != VK_SUCCESS)
        return *error = vkFailed("vkCreateCommandPool", r), false;
    VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cai.commandPool = pool_;
    cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cai.commandBufferCount = kFramesInFlight;
    if (VkResult r = vkAllocateCommandBuffers(vkDevice_, &cai, commandBuffers_.data()); r != VK_SUCCESS)
        return *error = vkFailed("vkAllocateCommandBuffers", r), false;
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // the first wait on each slot returns at once
    VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    for (uint32_t i = 0; i < kFramesInFlight; ++i) {
        if (VkResult r = vkCreateFence(vkDevice_, &fci, nullptr, &fences_[i]); r != VK_SUCCESS)
            return *error = vkFailed("vkCreateFence", r), false;
        if (VkResult r = vkCreateSemaphore(vkDevice_, &sci, nullptr, &acquired_[i]); r != VK_SUCCESS)
            return *error = vkFailed("vkCreateSemaphore", r), false;
    }
    return true;
}

VkPresentModeKHR VulkanViewerBackend::choosePresentMode() const {
    if (vsync_) return VK_PRESENT_MODE_FIFO_KHR;  // always supported
    uint32_t n = 0;
    vkGetPhysicalDeviceSurfacePresentModesKHR(physical_, surface_, &n, nullptr);
    std::vector<VkPresentModeKHR> modes(n);
    vkGetPhysicalDeviceSurfacePresentModesKHR(physical_, surface_, &n, modes.data());
    for (VkPresentModeKHR want : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
        for (VkPresentModeKHR m : modes)
            if (m == want) return m;
    return VK_PRESENT_MODE_FIFO_KHR;
}

void VulkanViewerBackend::destroySwapchainViews() {
    for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(vkDevice_, f, nullptr);
    for (VkImageView v : views_) vkDestroyImageView(vkDevice_, v, nullptr);
    for (VkSemaphore s : rendered_) vkDestroySemaphore(vkDevice_, s, nullptr);
    framebuffers_.clear();
    views_.clear();
    rendered_.clear();
    images_.clear();
}

// (Re)creates the swapchain at the framebuffer's size. The caller has waited for the device to be idle.
bool VulkanViewerBackend::createSwapchain(std::string* error) {
    VkSurfaceCapabilitiesKHR caps;
    if (VkResult r = vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical_, surface_, &caps); r != VK_SUCCESS)
        return *error = vkFailed("vkGetPhysicalDeviceSurfaceCapabilitiesKHR", r), false;
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        return *error = "vulkan: the surface's images cannot be transfer destinations (no blit target)", false;

    if (surfaceFormat_.format == VK_FORMAT_UNDEFINED) {
        // The display texture already holds sRGB-encoded bytes: a UNORM swapchain shows them unchanged.
        // The format is chosen once: ImGui's pipeline is built for a render pass of this format.
        uint32_t n = 0;
        vkGetPhysicalDeviceSurfaceFormatsKHR(physical_, surface_, &n, nullptr);
        std::vector<VkSurfaceFormatKHR> formats(n);
        vkGetPhysicalDeviceSurfaceFormatsKHR(physical_, surface_, &n, formats.data());
        for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
            for (const VkSurfaceFormatKHR& f : formats)
                if (f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR && !surfaceFormat_.format)
                    surfaceFormat_ = f;
        if (!surfaceFormat_.format)
            return *error = "vulkan: the surface offers neither B8G8R8A8_UNORM nor R8G8B8A8_UNORM", false;
    }

    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
    extent_ = caps.currentExtent;
    if (extent_.width == UINT32_MAX) {  // the surface takes the swapchain's size
        extent_.width = std::clamp(uint32_t(fbWidth), caps.minImageExtent.width, caps.maxImageExtent.width);
        extent_.height = std::clamp(uint32_t(fbHeight), caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    uint32_t imageCount = std::max(caps.minImageCount + 1, kFramesInFlight);
    if (caps.maxImageCount && imageCount > caps.maxImageCount) imageCount = caps.maxImageCount;

    VkSwapchainCreateInfoKHR sci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    sci.surface = surface_;
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
    sci.presentMode = choosePresentMode();
    sci.clipped = VK_TRUE;
    sci.oldSwapchain = swapchain_;
    VkSwapchainKHR fresh = VK_NULL_HANDLE;
    VkResult r = vkCreateSwapchainKHR(vkDevice_, &sci, nullptr, &fresh);
    destroySwapchainViews();
    if (swapchain_) vkDestroySwapchainKHR(vkDevice_, swapchain_, nullptr);
    swapchain_ = fresh;
    if (r != VK_SUCCESS) return *error = vkFailed("vkCreateSwapchainKHR", r), false;

    uint32_t n = 0;
    vkGetSwapchainImagesKHR(vkDevice_, swapchain_, &n, nullptr);
    images_.resize(n);
    vkGetSwapchainImagesKHR(vkDevice_, swapchain_, &n, images_.data());

    if (!renderPass_) {
        // Loads what the blit wrote (TRANSFER_DST) and hands the image to the presentation engine.
        VkAttachmentDescription attachment{};
        attachment.format = surfaceFormat_.format;
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
        if (VkResult rr = vkCreateRenderPass(vkDevice_, &rpi, nullptr, &renderPass_); rr != VK_SUCCESS)
            return *error = vkFailed("vkCreateRenderPass", rr), false;
    }

    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    for (VkImage image : images_) {
        VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vci.image = image;
        vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vci.format = surfaceFormat_.format;
        vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        if (VkResult rr = vkCreateImageView(vkDevice_, &vci, nullptr, &view); rr != VK_SUCCESS)
            return *error = vkFailed("vkCreateImageView (swapchain)", rr), false;
        views_.push_back(view);
        VkFramebufferCreateInfo fbi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fbi.renderPass = renderPass_;
        fbi.attachmentCount = 1;
        fbi.pAttachments = &view;
        fbi.width = extent_.width;
        fbi.height = extent_.height;
        fbi.layers = 1;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        if (VkResult rr = vkCreateFramebuffer(vkDevice_, &fbi, nullptr, &framebuffer); rr != VK_SUCCESS)
            return *error = vkFailed("vkCreateFramebuffer", rr), false;
        framebuffers_.push_back(framebuffer);
        VkSemaphore semaphore = VK_NULL_HANDLE;
        if (VkResult rr = vkCreateSemaphore(vkDevice_, &semaphoreInfo, nullptr, &semaphore); rr != VK_SUCCESS)
            return *error = vkFailed("vkCreateSemaphore", rr), false;
        rendered_.push_back(semaphore);
    }
    swapchainStale_ = false;
    return true;
}

// Records into a temporary command buffer, submits it and waits (set-up work only: fonts, layouts).
bool VulkanViewerBackend::submitNow(void (*record)(VkCommandBuffer, void*), void* user, std::string* error) {
    VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cai.commandPool = pool_;
    cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cai.commandBufferCount = 1;
    VkCommandBuffer cb = VK_NULL_HANDLE;
    if (VkResult r = vkAllocateCommandBuffers(vkDevice_, &cai, &cb); r != VK_SUCCESS)
        return *error = vkFailed("vkAllocateCommandBuffers", r), false;
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cb, &bi);
    record(cb, user);
    vkEndCommandBuffer(cb);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    VkResult r = vkQueueSubmit(queue_, 1, &si, VK_NULL_HANDLE);
    if (r == VK_SUCCESS) r = vkQueueWaitIdle(queue_);
    vkFreeCommandBuffers(vkDevice_, pool_, 1, &cb);
    if (r != VK_SUCCESS) return *error = vkFailed("vkQueueSubmit (set-up)", r), false;
    return true;
}

bool VulkanViewerBackend::createDisplay(uint32_t width, uint32_t height, std::string* error) {
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
    if (VkResult r = vkCreateImage(vkDevice_, &ici, nullptr, &display_.image); r != VK_SUCCESS)
        return *error = vkFailed("vkCreateImage (display texture)", r), false;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(vkDevice_, display_.image, &req);
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(physical_, &mem);
    uint32_t type = UINT32_MAX;
    for (VkMemoryPropertyFlags want : {VkMemoryPropertyFlags(VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT), VkMemoryPropertyFlags(0)})
        for (uint32_t i = 0; i < mem.memoryTypeCount && type == UINT32_MAX; ++i)
            if ((req.memoryTypeBits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & want) == want) type = i;
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = type;
    if (VkResult r = vkAllocateMemory(vkDevice_, &mai, nullptr, &display_.memory); r != VK_SUCCESS)
        return *error = vkFailed("vkAllocateMemory (display texture)", r), false;
    vkBindImageMemory(vkDevice_, display_.image, display_.memory, 0);

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
    if (!submitNow(toGeneral, &display_.image, error)) return false;

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
    if (display_.image) vkDestroyImage(vkDevice_, display_.image, nullptr);
    if (display_.memory) vkFreeMemory(vkDevice_, display_.memory, nullptr);
    display_ = {};
}

bool VulkanViewerBackend::initImGui(std::string* error) {
    if (!ImGui::GetCurrentContext()) return *error = "vulkan: no ImGui context (call ImGui::CreateContext first)", false;
    // Only the font atlas takes a descriptor set; a little room for the app's own ImGui::Image textures.
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
    VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    dpi.maxSets = 16;
    dpi.poolSizeCount = 1;
    dpi.pPoolSizes = &size;
    if (VkResult r = vkCreateDescriptorPool(vkDevice_, &dpi, nullptr, &imguiPool_); r != VK_SUCCESS)
        return *error = vkFailed("vkCreateDescriptorPool (ImGui)", r), false;

    imguiGlfw_ = ImGui_ImplGlfw_InitForVulkan(window_, true);
    if (!imguiGlfw_) return *error = "vulkan: ImGui_ImplGlfw_InitForVulkan failed", false;
    gImGuiErrorSink = &errorCallback_;
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = instance_;
    info.PhysicalDevice = physical_;
    info.Device = vkDevice_;
    info.QueueFamily = family_;
    info.Queue = queue_;
    info.DescriptorPool = imguiPool_;
    // ImGui keeps one vertex/index buffer pair per "image" and cycles through them per RenderDrawData;
    // what must not be overwritten is what a frame in flight reads, so frames in flight is the count.
    info.MinImageCount = kFramesInFlight;
    info.ImageCount = kFramesInFlight;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = onImGuiVkResult;
    imguiVulkan_ = ImGui_ImplVulkan_Init(&info, renderPass_);
    if (!imguiVulkan_) return *error = "vulkan: ImGui_ImplVulkan_Init failed", false;
    auto uploadFonts = [](VkCommandBuffer cb, void*) { ImGui_ImplVulkan_CreateFontsTexture(cb); };
    if (!submitNow(uploadFonts, nullptr, error)) return false;
    ImGui_ImplVulkan_DestroyFontUploadObjects();
    return true;
}

bool VulkanViewerBackend::create(std::string* error) {
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit())
        return *error = "no display: set DISPLAY or run under Xvfb (docs/viewer.md) [GLFW: " + lastGlfwError() + "]", false;
    glfwReady_ = true;
    if (!glfwVulkanSupported()) return *error = "vulkan: GLFW found no Vulkan loader / surface support", false;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_VISIBLE, options_.hidden ? GLFW_FALSE : GLFW_TRUE);
    window_ = glfwCreateWindow(int(options_.width), int(options_.height), options_.title.c_str(), nullptr, nullptr);
    if (!window_) return *error = "vulkan: glfwCreateWindow failed: " + lastGlfwError(), false;
    if (!createInstance(error) || !pickDevice(error) || !createDevice(error) || !createFrameObjects(error) ||
        !createSwapchain(error) || !initImGui(error))
        return false;
    return createDisplay(extent_.width, extent_.height, error);
}

VulkanViewerBackend::~VulkanViewerBackend() {
    if (vkDevice_) vkDeviceWaitIdle(vkDevice_);
    if (imguiVulkan_) ImGui_ImplVulkan_Shutdown();
    if (imguiGlfw_) ImGui_ImplGlfw_Shutdown();
    if (gImGuiErrorSink == &errorCallback_) gImGuiErrorSink = nullptr;
    if (device_) destroyDisplay();
    validation_.reset();
    device_.reset();  // Bricklight's objects on our VkDevice go first
    if (vkDevice_) {
        destroySwapchainViews();
        if (swapchain_) vkDestroySwapchainKHR(vkDevice_, swapchain_, nullptr);
        if (renderPass_) vkDestroyRenderPass(vkDevice_, renderPass_, nullptr);
        if (imguiPool_) vkDestroyDescriptorPool(vkDevice_, imguiPool_, nullptr);
        for (uint32_t i = 0; i < kFramesInFlight; ++i) {
            if (fences_[i]) vkDestroyFence(vkDevice_, fences_[i], nullptr);
            if (acquired_[i]) vkDestroySemaphore(vkDevice_, acquired_[i], nullptr);
        }
        if (pool_) vkDestroyCommandPool(vkDevice_, pool_, nullptr);
        vkDestroyDevice(vkDevice_, nullptr);
    }
    if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
    if (window_) glfwDestroyWindow(window_);
    if (glfwReady_) glfwTerminate();
}

bool VulkanViewerBackend::beginFrame() {
    if (inFrame_) return report("vulkan viewer: beginFrame called twice without endFrame"), false;
    int fbWidth = 0, fbHeight = 0;
    glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
    if (fbWidth <= 0 || fbHeight <= 0) return false;  // minimized: nothing can be presented

    vkWaitForFences(vkDevice_, 1, &fences_[slot_], VK_TRUE, UINT64_MAX);
    std::string error;
    for (int attempt = 0;; ++attempt) {
        if (swapchainStale_ || uint32_t(fbWidth) != extent_.width || uint32_t(fbHeight) != extent_.height) {
            vkDeviceWaitIdle(vkDevice_);
            if (!createSwapchain(&error)) return report(error), false;
        }
        if (display_.width != extent_.width || display_.height != extent_.height) {
            destroyDisplay();
            if (!createDisplay(extent_.width, extent_.height, &error)) return report(error), false;
        }
        VkResult r = vkAcquireNextImageKHR(vkDevice_, swapchain_, UINT64_MAX, acquired_[slot_], VK_NULL_HANDLE, &imageIndex_);
        if (r == VK_SUCCESS) break;
        if (r == VK_SUBOPTIMAL_KHR) {  // usable now; rebuilt at the next frame
            swapchainStale_ = true;
            break;
        }
        if (r != VK_ERROR_OUT_OF_DATE_KHR || attempt == 2) return report(vkFailed("vkAcquireNextImageKHR", r)), false;
        swapchainStale_ = true;  // acquire signalled nothing; rebuild and try again
    }
    vkResetFences(vkDevice_, 1, &fences_[slot_]);  // only now: a frame that returned early submits nothing

    VkCommandBuffer cb = commandBuffers_[slot_];
    vkResetCommandBuffer(cb, 0);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cb, &bi);
    vulkan::setCommandBuffer(*device_, cb);
    inFrame_ = true;
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    return true;
}

void VulkanViewerBackend::endFrame(ImDrawData* ui) {
    if (!inFrame_) return report("vulkan viewer: endFrame without a successful beginFrame");
    inFrame_ = false;
    VkCommandBuffer cb = commandBuffers_[slot_];
    VkImage target = images_[imageIndex_];

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
    before[1].srcStageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;  // chained to the semaphore wait below
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
    VkImageBlit region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.srcOffsets[1] = {int32_t(display_.width), int32_t(display_.height), 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstOffsets[1] = {int32_t(extent_.width), int32_t(extent_.height), 1};
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

    VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rbi.renderPass = renderPass_;
    rbi.framebuffer = framebuffers_[imageIndex_];
    rbi.renderArea.extent = extent_;
    vkCmdBeginRenderPass(cb, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    if (ui) ImGui_ImplVulkan_RenderDrawData(ui, cb);
    vkCmdEndRenderPass(cb);
    vkEndCommandBuffer(cb);

    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait.semaphore = acquired_[slot_];
    wait.stageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
    VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signal.semaphore = rendered_[imageIndex_];
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
    if (VkResult r = vkQueueSubmit2(queue_, 1, &si, fences_[slot_]); r != VK_SUCCESS)
        report(vkFailed("vkQueueSubmit2", r));

    VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    pi.waitSemaphoreCount = 1;
    pi.pWaitSemaphores = &rendered_[imageIndex_];
    pi.swapchainCount = 1;
    pi.pSwapchains = &swapchain_;
    pi.pImageIndices = &imageIndex_;
    VkResult r = vkQueuePresentKHR(queue_, &pi);
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR)
        swapchainStale_ = true;
    else if (r != VK_SUCCESS)
        report(vkFailed("vkQueuePresentKHR", r));

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
