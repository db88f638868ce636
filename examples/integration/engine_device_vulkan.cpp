// Vulkan as an engine sets it up: the application owns the instance (with the validation layer and a
// debug messenger when they are installed), the VkDevice, the queue, the command buffers and the frame
// pacing. Bricklight's backend is created *embedded* on those objects and records into the application's
// command buffer (vulkan::setCommandBuffer); the application submits it. docs/backend_vulkan.md,
// "Embedded mode", lists the rules this file follows.
#include <array>
#include <cstring>

#include "bricklight/rhi_validation.h"
#include "bricklight/rhi_vulkan.h"
#include "engine_device.h"

namespace integration {

namespace {

using bricklight::rhi::Severity;

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

// A queue family that does graphics and compute: Bricklight records both kinds of work into one stream.
int64_t graphicsComputeFamily(VkPhysicalDevice device) {
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &n, families.data());
    for (uint32_t i = 0; i < n; ++i)
        if ((families[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) == (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT))
            return i;
    return -1;
}

VKAPI_ATTR VkBool32 VKAPI_CALL onLayerMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    static_cast<MessageLog*>(user)->add("vulkan layer", Severity::Error, data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

class VulkanEngineDevice final : public EngineDevice {
public:
    ~VulkanEngineDevice() override {
        if (device_) vkDeviceWaitIdle(device_);
        // Bricklight's objects go first (the backend destroys what it created on our VkDevice), ours after.
        validation_.reset();
        backend_.reset();
        if (device_) {
            for (VkFence f : fences_)
                if (f) vkDestroyFence(device_, f, nullptr);
            if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
            vkDestroyDevice(device_, nullptr);
        }
        if (messenger_) {
            auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
            if (destroy) destroy(instance_, messenger_, nullptr);
        }
        if (instance_) vkDestroyInstance(instance_, nullptr);
    }

    bool create(std::string* error);

    void beginFrame() override {
        // Two frames in flight, as the backend keeps: wait until this slot's command buffer is free again.
        slot_ = (slot_ + 1) % kFramesInFlight;
        vkWaitForFences(device_, 1, &fences_[slot_], VK_TRUE, UINT64_MAX);
        vkResetFences(device_, 1, &fences_[slot_]);
        VkCommandBuffer cb = commandBuffers_[slot_];
        vkResetCommandBuffer(cb, 0);
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        vkBeginCommandBuffer(cb, &begin);
        // An engine would record its own passes here too, before and after Bricklight's; the backend tracks
        // only its own calls, so work of ours that touches Bricklight resources needs our own barriers.
        // setCommandBuffer wants the backend's device, not the validation wrapper around it.
        bricklight::vulkan::setCommandBuffer(*backend_, cb);
    }

    void endFrame() override {
        VkCommandBuffer cb = commandBuffers_[slot_];
        vkEndCommandBuffer(cb);
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cb;
        vkQueueSubmit(queue_, 1, &submit, fences_[slot_]);
        // After our submission: the backend fences its per-frame memory (constants, uploads, descriptors)
        // behind what we just submitted and recycles it two frames later.
        device().endFrame();
    }

    void finish() override {
        bricklight::vulkan::setCommandBuffer(*backend_, VK_NULL_HANDLE);  // read-backs use the backend's own again
        device().waitIdle();
    }

private:
    static constexpr uint32_t kFramesInFlight = 2;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t family_ = 0;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::array<VkCommandBuffer, kFramesInFlight> commandBuffers_{};
    std::array<VkFence, kFramesInFlight> fences_{};
    uint32_t slot_ = 0;
    VkPhysicalDeviceFeatures enabled_{};
    std::unique_ptr<bricklight::rhi::IDevice> backend_;
};

bool VulkanEngineDevice::create(std::string* error) {
    auto fail = [&](const std::string& m) {
        *error = m;
        return false;
    };
    uint32_t loaderVersion = VK_API_VERSION_1_0;
    vkEnumerateInstanceVersion(&loaderVersion);
    if (loaderVersion < VK_API_VERSION_1_3) return fail("the Vulkan loader is older than 1.3");

    // 1. Instance: the validation layer and a messenger that counts what it says, when installed. The
    //    messenger is also chained into vkCreateInstance so that instance creation itself is checked.
    std::vector<const char*> layers, extensions;
    const bool validation = hasLayer("VK_LAYER_KHRONOS_validation");
    const bool debugUtils = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (validation) layers.push_back("VK_LAYER_KHRONOS_validation");
    if (debugUtils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = onLayerMessage;
    messengerInfo.pUserData = messages_.get();
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "bricklight_integration";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ici.pApplicationInfo = &app;
    ici.enabledLayerCount = uint32_t(layers.size());
    ici.ppEnabledLayerNames = layers.data();
    ici.enabledExtensionCount = uint32_t(extensions.size());
    ici.ppEnabledExtensionNames = extensions.data();
    if (debugUtils) ici.pNext = &messengerInfo;
    if (vkCreateInstance(&ici, nullptr, &instance_) != VK_SUCCESS) return fail("vkCreateInstance failed");
    if (debugUtils) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!create || create(instance_, &messengerInfo, nullptr, &messenger_) != VK_SUCCESS) return fail("cannot create the debug messenger");
    }

    // 2. Physical device: Vulkan 1.3 with synchronization2 and dynamic rendering (the backend needs both)
    //    and a graphics + compute queue; a real GPU before a software one.
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
        if (p.apiVersion < VK_API_VERSION_1_3 || !f13.synchronization2 || !f13.dynamicRendering || graphicsComputeFamily(pd) < 0) continue;
        const int score = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU     ? 3
                          : p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ? 2
                                                                                   : 1;
        if (score > bestScore) bestScore = score, physical_ = pd;
    }
    if (!physical_) return fail("no Vulkan 1.3 device with synchronization2, dynamicRendering and a graphics+compute queue");
    family_ = uint32_t(graphicsComputeFamily(physical_));

    // 3. Device: the two required features, plus the optional ones the backend can use when present
    //    (vulkan::usefulFeatures; it cannot query what an application enabled, so EmbeddedDesc tells it below).
    enabled_ = bricklight::vulkan::usefulFeatures(physical_);
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.synchronization2 = VK_TRUE;
    f13.dynamicRendering = VK_TRUE;
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.pNext = &f13;
    f2.features = enabled_;
    // Push descriptors save the backend a descriptor pool per frame; optional.
    std::vector<const char*> deviceExtensions;
    const bool pushDescriptors = hasDeviceExtension(physical_, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    if (pushDescriptors) deviceExtensions.push_back(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = family_;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.pNext = &f2;
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = uint32_t(deviceExtensions.size());
    dci.ppEnabledExtensionNames = deviceExtensions.data();
    if (vkCreateDevice(physical_, &dci, nullptr, &device_) != VK_SUCCESS) return fail("vkCreateDevice failed");
    vkGetDeviceQueue(device_, family_, 0, &queue_);

    // 4. The application's command buffers and the fences that pace them.
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = family_;
    if (vkCreateCommandPool(device_, &pci, nullptr, &pool_) != VK_SUCCESS) return fail("vkCreateCommandPool failed");
    VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cai.commandPool = pool_;
    cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cai.commandBufferCount = kFramesInFlight;
    if (vkAllocateCommandBuffers(device_, &cai, commandBuffers_.data()) != VK_SUCCESS) return fail("vkAllocateCommandBuffers failed");
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // the first wait on each slot returns at once
    for (VkFence& f : fences_)
        if (vkCreateFence(device_, &fci, nullptr, &f) != VK_SUCCESS) return fail("vkCreateFence failed");

    // 5. Bricklight on our objects, and the validation wrapper on top. Until the wrapper exists the backend
    //    reports to the EmbeddedDesc callback; the wrapper then takes its messages over.
    bricklight::vulkan::EmbeddedDesc e;
    e.instance = instance_;
    e.physicalDevice = physical_;
    e.device = device_;
    e.queue = queue_;
    e.queueFamilyIndex = family_;
    e.enabledFeatures = &enabled_;
    e.pushDescriptorEnabled = pushDescriptors;
    e.debugUtilsEnabled = debugUtils;
    std::shared_ptr<MessageLog> log = messages_;
    e.errorCallback = [log](Severity s, const std::string& m) { log->add("vulkan backend", s, m); };
    backend_ = bricklight::vulkan::createEmbeddedDevice(e);
    if (!backend_) return fail("createEmbeddedDevice failed (see the messages above)");
    validation_ = bricklight::rhi::createValidationDevice(*backend_);
    validation_->setErrorCallback([log](Severity s, const std::string& m) { log->add("rhi", s, m); });
    description_ = "vulkan (application's own VkDevice, embedded) on " + backend_->capabilities().deviceName +
                   (validation ? ", validation layer on" : ", validation layer NOT installed");
    return true;
}

}  // namespace

std::unique_ptr<EngineDevice> createVulkanEngineDevice(std::string* error) {
    auto d = std::make_unique<VulkanEngineDevice>();
    if (!d->create(error)) return nullptr;
    return d;
}

}  // namespace integration
