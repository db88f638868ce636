#include "vulkan_context.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "bricklight/rhi_vulkan.h"
#include "vulkan_errors.h"

namespace bricklight::viewer {

namespace {

using rhi::Severity;

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

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* callback = static_cast<rhi::ErrorCallback*>(user);
    const std::string message = std::string("vulkan validation: ") + (data && data->pMessage ? data->pMessage : "");
    if (*callback) (*callback)(Severity::Error, message);
    return VK_FALSE;
}

}  // namespace

bool VulkanContext::create(GLFWwindow* window, bool validation, rhi::ErrorCallback* errors, std::string* error) {
    return createInstance(window, validation, errors, error) && pickPhysicalDevice(error) && createDevice(error);
}

void VulkanContext::destroy() {
    if (device_) vkDestroyDevice(device_, nullptr);
    if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
    if (messenger_) {
        auto destroyMessenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroyMessenger) destroyMessenger(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
    device_ = VK_NULL_HANDLE;
    queue_ = VK_NULL_HANDLE;
    physical_ = VK_NULL_HANDLE;
    surface_ = VK_NULL_HANDLE;
    messenger_ = VK_NULL_HANDLE;
    instance_ = VK_NULL_HANDLE;
}

bool VulkanContext::createInstance(GLFWwindow* window, bool validation, rhi::ErrorCallback* errors,
                                   std::string* error) {
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
    if (validation || (env && std::strcmp(env, "1") == 0)) {
        if (hasLayer("VK_LAYER_KHRONOS_validation"))
            layers.push_back("VK_LAYER_KHRONOS_validation");
        else
            (*errors)(Severity::Warning, "vulkan: VK_LAYER_KHRONOS_validation is not installed; validation is off");
    }
    debugUtils_ = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (debugUtils_) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = onValidationMessage;
    messengerInfo.pUserData = errors;
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
        auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!createMessenger || createMessenger(instance_, &messengerInfo, nullptr, &messenger_) != VK_SUCCESS)
            return *error = "vulkan: cannot create the debug messenger", false;
    }
    if (VkResult r = glfwCreateWindowSurface(instance_, window, nullptr, &surface_); r != VK_SUCCESS)
        return *error = vkFailed("glfwCreateWindowSurface", r) + ": " + lastGlfwError(), false;
    return true;
}

bool VulkanContext::pickPhysicalDevice(std::string* error) {
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

bool VulkanContext::createDevice(std::string* error) {
    // The optional features the standalone device enables, so that the embedded one can use the same shader
    // paths; EmbeddedDesc tells it which are on.
    enabled_ = vulkan::usefulFeatures(physical_);
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
    if (VkResult r = vkCreateDevice(physical_, &dci, nullptr, &device_); r != VK_SUCCESS)
        return *error = vkFailed("vkCreateDevice", r), false;
    vkGetDeviceQueue(device_, family_, 0, &queue_);
    return true;
}

bool VulkanContext::submitNow(VkCommandPool pool, void (*record)(VkCommandBuffer, void*), void* user,
                              std::string* error) const {
    VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cai.commandPool = pool;
    cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cai.commandBufferCount = 1;
    VkCommandBuffer cb = VK_NULL_HANDLE;
    if (VkResult r = vkAllocateCommandBuffers(device_, &cai, &cb); r != VK_SUCCESS)
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
    vkFreeCommandBuffers(device_, pool, 1, &cb);
    if (r != VK_SUCCESS) return *error = vkFailed("vkQueueSubmit (set-up)", r), false;
    return true;
}

}  // namespace bricklight::viewer
