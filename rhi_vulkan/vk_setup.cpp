// Instance, physical device and device creation; capabilities; the debug messenger; the public factories.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "vk_device.h"
#include "vk_formats.h"

namespace bricklight::vulkan::detail {

void Reporter::report(rhi::Severity severity, const std::string& message) const {
    if (callback) {
        callback(severity, message);
        return;
    }
    const char* tag = severity == rhi::Severity::Error ? "error" : severity == rhi::Severity::Warning ? "warning" : "info";
    fprintf(stderr, "bricklight vulkan %s: %s\n", tag, message.c_str());
}

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL debugMessenger(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
    auto* reporter = static_cast<Reporter*>(user);
    reporter->validationMessages++;
    reporter->report(rhi::Severity::Error, std::string("vulkan validation: ") + (data->pMessage ? data->pMessage : ""));
    return VK_FALSE;
}

bool envFlag(const char* name) {
    const char* v = getenv(name);
    return v && *v && strcmp(v, "0") != 0;
}

bool hasInstanceLayer(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    for (auto& l : layers)
        if (strcmp(l.layerName, name) == 0) return true;
    return false;
}

bool hasInstanceExtension(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> exts(n);
    vkEnumerateInstanceExtensionProperties(nullptr, &n, exts.data());
    for (auto& e : exts)
        if (strcmp(e.extensionName, name) == 0) return true;
    return false;
}

bool hasDeviceExtension(VkPhysicalDevice pd, const char* name) {
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> exts(n);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data());
    for (auto& e : exts)
        if (strcmp(e.extensionName, name) == 0) return true;
    return false;
}

// One queue does everything: Bricklight needs graphics + compute in one stream, and presenting from the same
// queue needs no ownership transfer of the swapchain image.
int64_t findQueueFamily(VkPhysicalDevice pd, VkSurfaceKHR surface) {
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
    const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (uint32_t i = 0; i < n; ++i) {
        VkBool32 present = VK_TRUE;
        if (surface) vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, surface, &present);
        if ((families[i].queueFlags & need) == need && present) return i;
    }
    return -1;
}

int typeScore(VkPhysicalDeviceType type, bool preferSoftware) {
    if (preferSoftware) return type == VK_PHYSICAL_DEVICE_TYPE_CPU ? 10 : 0;
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
        default: return 0;
    }
}

}  // namespace

bool VulkanDevice::fail(const std::string& message) const {
    reporter_->report(rhi::Severity::Error, message);
    return false;
}

void VulkanDevice::warn(const std::string& message) const { reporter_->report(rhi::Severity::Warning, message); }

std::string VulkanDevice::quoted(const char* label) {
    return label && *label ? std::string(" '") + label + "'" : std::string();
}

// Bricklight's start-up (createDevice and createVulkanObjects): instance, messenger, surface, physical device,
// queue family, device. Fills `out` as it goes (the caller destroys a partial result); failures go to `reporter`.
// `statistics`: the pipeline executable properties extension and feature when the device has them (*statisticsOn).
bool startVulkan(const StartupDesc& d, Reporter& reporter, bool statistics, VulkanObjects& out, bool* statisticsOn) {
    auto fail = [&](const std::string& message) {
        reporter.report(rhi::Severity::Error, message);
        return false;
    };
    const bool validation = d.enableValidation || envFlag("BRICKLIGHT_VK_VALIDATION");
    const bool syncValidation = d.enableSyncValidation || envFlag("BRICKLIGHT_VK_SYNC_VALIDATION");
    uint32_t apiVersion = VK_API_VERSION_1_0;
    vkEnumerateInstanceVersion(&apiVersion);
    if (apiVersion < VK_API_VERSION_1_3)
        return fail("createDevice: the Vulkan loader supports version " + std::to_string(VK_API_VERSION_MAJOR(apiVersion)) + "." +
                    std::to_string(VK_API_VERSION_MINOR(apiVersion)) + "; Vulkan 1.3 is required");

    std::vector<const char*> layers, extensions = d.instanceExtensions;
    if (validation) {
        if (hasInstanceLayer("VK_LAYER_KHRONOS_validation"))
            layers.push_back("VK_LAYER_KHRONOS_validation");
        else
            fail("createDevice: validation requested but VK_LAYER_KHRONOS_validation is not installed");
    }
    out.validationEnabled = !layers.empty();
    out.debugUtilsEnabled = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (out.debugUtilsEnabled) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = debugMessenger;
    messengerInfo.pUserData = &reporter;

    VkValidationFeatureEnableEXT syncFeature = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &syncFeature;

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = d.applicationName;
    app.pEngineName = "bricklight";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ici.pApplicationInfo = &app;
    ici.enabledLayerCount = static_cast<uint32_t>(layers.size());
    ici.ppEnabledLayerNames = layers.data();
    ici.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    ici.ppEnabledExtensionNames = extensions.data();
    const bool useMessenger = out.debugUtilsEnabled && !layers.empty();
    if (useMessenger) {
        ici.pNext = &messengerInfo;  // chained: instance creation is checked too
        if (syncValidation) messengerInfo.pNext = &features;
    }
    if (VkResult r = vkCreateInstance(&ici, nullptr, &out.instance); r != VK_SUCCESS)
        return fail("createDevice: vkCreateInstance failed (VkResult " + std::to_string(r) + ")");
    if (useMessenger) {
        messengerInfo.pNext = nullptr;
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(out.instance, "vkCreateDebugUtilsMessengerEXT"));
        if (create) create(out.instance, &messengerInfo, nullptr, &out.messenger);
    }
    if (d.createSurface) {
        if (VkResult r = d.createSurface(out.instance, &out.surface); r != VK_SUCCESS || !out.surface)
            return fail("createDevice: the window's surface could not be created (VkResult " + std::to_string(r) + ")");
    }

    // Pick the physical device: Vulkan 1.3, sync2 + dynamic rendering, the asked-for extensions, a graphics+compute
    // queue (that presents to the surface).
    std::string filter = d.deviceNameContains;
    if (const char* env = getenv("BRICKLIGHT_VK_DEVICE"); env && *env) filter = env;
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(out.instance, &count, nullptr);
    std::vector<VkPhysicalDevice> candidates(count);
    vkEnumeratePhysicalDevices(out.instance, &count, candidates.data());
    int bestScore = -1;
    std::string rejected;
    for (VkPhysicalDevice pd : candidates) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd, &p);
        VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        f2.pNext = &f13;
        vkGetPhysicalDeviceFeatures2(pd, &f2);
        std::string why;
        if (p.apiVersion < VK_API_VERSION_1_3) why = "Vulkan 1.3 not supported";
        else if (!f13.synchronization2 || !f13.dynamicRendering) why = "no synchronization2/dynamicRendering";
        else if (findQueueFamily(pd, out.surface) < 0) why = out.surface ? "no graphics+compute queue that presents to the window" : "no graphics+compute queue";
        else if (!filter.empty() && std::string(p.deviceName).find(filter) == std::string::npos)
            why = "name does not contain '" + filter + "'";
        for (const char* e : d.deviceExtensions)
            if (why.empty() && !hasDeviceExtension(pd, e)) why = std::string("no ") + e;
        if (!why.empty()) {
            rejected += std::string(rejected.empty() ? "" : "; ") + p.deviceName + ": " + why;
            continue;
        }
        int score = typeScore(p.deviceType, d.preferSoftware);
        if (score > bestScore) {
            bestScore = score;
            out.physicalDevice = pd;
        }
    }
    if (!out.physicalDevice)
        return fail("createDevice: no usable Vulkan device" + (rejected.empty() ? std::string() : " (" + rejected + ")"));
    out.queueFamilyIndex = static_cast<uint32_t>(findQueueFamily(out.physicalDevice, out.surface));

    // Features: the required ones plus every optional one the contract can use.
    out.enabledFeatures = usefulFeatures(out.physicalDevice);
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.synchronization2 = VK_TRUE;
    f13.dynamicRendering = VK_TRUE;
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.pNext = &f13;
    f2.features = out.enabledFeatures;

    std::vector<const char*> devExt = d.deviceExtensions;
    // Shader statistics for tuning (a diagnostic: the driver's register counts and the like per pipeline).
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executableInfo{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
    statistics = statistics && hasDeviceExtension(out.physicalDevice, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    if (statistics) {
        executableInfo.pipelineExecutableInfo = VK_TRUE;
        f13.pNext = &executableInfo;
        devExt.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    }
    if (statisticsOn) *statisticsOn = statistics;
    const bool noPush = d.disablePushDescriptors || envFlag("BRICKLIGHT_VK_NO_PUSH_DESCRIPTORS");
    out.pushDescriptorEnabled = !noPush && hasDeviceExtension(out.physicalDevice, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
    if (out.pushDescriptorEnabled) devExt.push_back(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);

    float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = out.queueFamilyIndex;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.pNext = &f2;
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = static_cast<uint32_t>(devExt.size());
    dci.ppEnabledExtensionNames = devExt.data();
    if (VkResult r = vkCreateDevice(out.physicalDevice, &dci, nullptr, &out.device); r != VK_SUCCESS)
        return fail("createDevice: vkCreateDevice failed (VkResult " + std::to_string(r) + ")");
    vkGetDeviceQueue(out.device, out.queueFamilyIndex, 0, &out.queue);
    return true;
}

std::unique_ptr<VulkanDevice> VulkanDevice::createStandalone(const DeviceOptions& options) {
    std::unique_ptr<VulkanDevice> dev(new VulkanDevice());
    dev->reporter_->callback = options.errorCallback;
    dev->ownsDevice_ = true;
    StartupDesc sd;
    sd.enableValidation = options.enableValidation;
    sd.enableSyncValidation = options.enableSyncValidation;
    sd.preferSoftware = options.preferSoftware;
    sd.deviceNameContains = options.deviceNameContains;
    sd.disablePushDescriptors = options.disablePushDescriptors;
    VulkanObjects o;
    bool statistics = false;
    const bool started = startVulkan(sd, *dev->reporter_, envFlag("BRICKLIGHT_VK_SHADER_STATISTICS"), o, &statistics);
    // The device owns what was made, also on failure (its destructor destroys it).
    dev->instance_ = o.instance;
    dev->messenger_ = o.messenger;
    dev->physical_ = o.physicalDevice;
    dev->device_ = o.device;
    dev->queue_ = o.queue;
    dev->queueFamily_ = o.queueFamilyIndex;
    dev->enabled_ = o.enabledFeatures;
    dev->pushDescriptors_ = o.pushDescriptorEnabled;
    dev->debugUtils_ = o.debugUtilsEnabled;
    if (!started) return nullptr;
    dev->barrierReuse_ = !(options.disableBarrierReuse || envFlag("BRICKLIGHT_VK_NO_BARRIER_REUSE"));
    if (statistics) {
        dev->executableProperties_ = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
            vkGetDeviceProcAddr(dev->device_, "vkGetPipelineExecutablePropertiesKHR"));
        dev->executableStatistics_ = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
            vkGetDeviceProcAddr(dev->device_, "vkGetPipelineExecutableStatisticsKHR"));
    }
    if (!dev->initDevice()) return nullptr;
    return dev;
}

std::unique_ptr<VulkanDevice> VulkanDevice::createEmbedded(const EmbeddedDesc& desc) {
    std::unique_ptr<VulkanDevice> dev(new VulkanDevice());
    dev->reporter_->callback = desc.errorCallback;
    if (!desc.instance || !desc.physicalDevice || !desc.device || !desc.queue) {
        dev->fail("createEmbeddedDevice: instance, physicalDevice, device and queue must all be set");
        return nullptr;
    }
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(desc.physicalDevice, &p);
    if (p.apiVersion < VK_API_VERSION_1_3) {
        dev->fail(std::string("createEmbeddedDevice: '") + p.deviceName + "' does not support Vulkan 1.3");
        return nullptr;
    }
    dev->instance_ = desc.instance;
    dev->physical_ = desc.physicalDevice;
    dev->device_ = desc.device;
    dev->queue_ = desc.queue;
    dev->queueFamily_ = desc.queueFamilyIndex;
    if (desc.enabledFeatures) dev->enabled_ = *desc.enabledFeatures;
    dev->pushDescriptors_ = desc.pushDescriptorEnabled;
    dev->debugUtils_ = desc.debugUtilsEnabled;
    if (!dev->initDevice()) return nullptr;
    return dev;
}

void VulkanDevice::loadFunctions() {
    if (pushDescriptors_) {
        pushDescriptorSet_ =
            reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
        if (!pushDescriptorSet_) pushDescriptors_ = false;
    }
    if (debugUtils_) {
        setObjectName_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
        beginLabel_ = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
        endLabel_ = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
        debugUtils_ = setObjectName_ && beginLabel_ && endLabel_;
    }
}

bool VulkanDevice::initDevice() {
    vkGetPhysicalDeviceProperties(physical_, &props_);
    vkGetPhysicalDeviceMemoryProperties(physical_, &memProps_);
    loadFunctions();
    queryCapabilities();
    createFrames();
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    if (vkCreateFence(device_, &fci, nullptr, &syncFence_) != VK_SUCCESS) return fail("createDevice: vkCreateFence failed");
    return true;
}

void VulkanDevice::queryCapabilities() {
    VkPhysicalDevicePushDescriptorPropertiesKHR push{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PUSH_DESCRIPTOR_PROPERTIES_KHR};
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    driver.pNext = pushDescriptors_ ? &push : nullptr;
    VkPhysicalDeviceMaintenance3Properties m3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
    m3.pNext = &driver;
    VkPhysicalDeviceMaintenance4Properties m4{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES};
    m4.pNext = &m3;
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    p2.pNext = &m4;
    vkGetPhysicalDeviceProperties2(physical_, &p2);
    maxPushDescriptors_ = pushDescriptors_ ? push.maxPushDescriptors : 0;
    VkDeviceSize largestHeap = 0;
    for (uint32_t i = 0; i < memProps_.memoryHeapCount; ++i)
        if (memProps_.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            largestHeap = std::max(largestHeap, memProps_.memoryHeaps[i].size);
    maxAllocationBytes_ = std::min<uint64_t>(m3.maxMemoryAllocationSize, largestHeap);
    maxBufferBytes_ = std::min<uint64_t>(m4.maxBufferSize, maxAllocationBytes_);

    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &n, families.data());
    timestampValidBits_ = queueFamily_ < n ? families[queueFamily_].timestampValidBits : 0;

    const VkPhysicalDeviceLimits& l = props_.limits;
    caps_.backendName = "vulkan";
    caps_.deviceName = std::string(props_.deviceName) + " (" + driver.driverName + " " + driver.driverInfo + ")";
    caps_.limits.maxTextureSize2D = l.maxImageDimension2D;
    caps_.limits.maxTextureSize3D = l.maxImageDimension3D;
    caps_.limits.maxTextureArrayLayers = l.maxImageArrayLayers;
    for (int i = 0; i < 3; ++i) {
        caps_.limits.maxComputeGroupCount[i] = l.maxComputeWorkGroupCount[i];
        caps_.limits.maxComputeGroupSize[i] = l.maxComputeWorkGroupSize[i];
    }
    caps_.limits.maxComputeGroupInvocations = l.maxComputeWorkGroupInvocations;
    caps_.limits.maxComputeSharedMemoryBytes = l.maxComputeSharedMemorySize;
    caps_.limits.maxStorageBufferRange = l.maxStorageBufferRange;
    caps_.limits.maxColorTargets = std::min<uint32_t>(l.maxColorAttachments, rhi::kMaxColorTargets);
    caps_.limits.minStorageBufferOffsetAlignment = static_cast<uint32_t>(l.minStorageBufferOffsetAlignment);
    caps_.limits.minUniformBufferOffsetAlignment = static_cast<uint32_t>(l.minUniformBufferOffsetAlignment);
    for (size_t i = 1; i < static_cast<size_t>(rhi::Format::Count); ++i) {
        auto f = static_cast<rhi::Format>(i);
        VkFormatProperties fp;
        vkGetPhysicalDeviceFormatProperties(physical_, toVkFormat(f), &fp);
        caps_.formatSupport[i] = formatSupportBits(f, fp.optimalTilingFeatures);
    }
    caps_.geometryShader = enabled_.geometryShader;
    caps_.timestamps = l.timestampComputeAndGraphics && timestampValidBits_ > 0;
}

VulkanDevice::~VulkanDevice() {
    if (device_) {
        if (!appCommandBuffer_) waitForGpu();
        vkDeviceWaitIdle(device_);
        for (auto& [ticket, rb] : readbacks_) {
            vkDestroyBuffer(device_, rb.buffer, nullptr);
            vkFreeMemory(device_, rb.memory, nullptr);
        }
        readbacks_.clear();
        for (auto& f : frames_) {
            for (auto& fn : f.garbage) fn();
            f.garbage.clear();
        }
        for (auto& [id, t] : textures_) {
            for (auto& v : t->views) vkDestroyImageView(device_, v.second, nullptr);
            if (!t->wrapped) {
                vkDestroyImage(device_, t->image, nullptr);
                vkFreeMemory(device_, t->memory, nullptr);
            }
        }
        for (auto& [id, b] : buffers_)
            if (!b->wrapped) {
                vkDestroyBuffer(device_, b->buffer, nullptr);
                vkFreeMemory(device_, b->memory, nullptr);
            }
        for (auto& [id, s] : samplers_) vkDestroySampler(device_, s->sampler, nullptr);
        for (auto& [id, s] : shaders_) vkDestroyShaderModule(device_, s->module, nullptr);
        for (auto& [key, p] : pipelines_) vkDestroyPipeline(device_, p.pipeline, nullptr);
        for (auto& [key, l] : setLayouts_) {
            vkDestroyPipelineLayout(device_, l->pipelineLayout, nullptr);
            vkDestroyDescriptorSetLayout(device_, l->setLayout, nullptr);
        }
        destroyFrames();
        if (syncFence_) vkDestroyFence(device_, syncFence_, nullptr);
        if (ownsDevice_) vkDestroyDevice(device_, nullptr);
    }
    if (ownsDevice_ && instance_) {
        if (messenger_) {
            auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
            if (destroy) destroy(instance_, messenger_, nullptr);
        }
        vkDestroyInstance(instance_, nullptr);
    }
}

}  // namespace bricklight::vulkan::detail

namespace bricklight::vulkan {

using detail::VulkanDevice;

std::unique_ptr<rhi::IDevice> createDevice(const DeviceOptions& options) {
    return VulkanDevice::createStandalone(options);
}
std::unique_ptr<rhi::IDevice> createEmbeddedDevice(const EmbeddedDesc& desc) {
    return VulkanDevice::createEmbedded(desc);
}

std::optional<VulkanObjects> createVulkanObjects(const StartupDesc& desc) {
    auto reporter = std::make_shared<detail::Reporter>();
    reporter->callback = desc.errorCallback;
    VulkanObjects objects;
    objects.messengerTarget = reporter;
    if (!detail::startVulkan(desc, *reporter, false, objects, nullptr)) {
        destroyVulkanObjects(objects);
        return std::nullopt;
    }
    return objects;
}

void destroyVulkanObjects(VulkanObjects& o) {
    if (o.device) vkDestroyDevice(o.device, nullptr);
    if (o.instance) {
        if (o.surface) vkDestroySurfaceKHR(o.instance, o.surface, nullptr);
        if (o.messenger) {
            auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(o.instance, "vkDestroyDebugUtilsMessengerEXT"));
            if (destroy) destroy(o.instance, o.messenger, nullptr);
        }
        vkDestroyInstance(o.instance, nullptr);
    }
    o = VulkanObjects{};
}

EmbeddedDesc embeddedDesc(const VulkanObjects& o, rhi::ErrorCallback errorCallback) {
    EmbeddedDesc e;
    e.instance = o.instance;
    e.physicalDevice = o.physicalDevice;
    e.device = o.device;
    e.queue = o.queue;
    e.queueFamilyIndex = o.queueFamilyIndex;
    e.errorCallback = std::move(errorCallback);
    e.enabledFeatures = &o.enabledFeatures;
    e.pushDescriptorEnabled = o.pushDescriptorEnabled;
    e.debugUtilsEnabled = o.debugUtilsEnabled;
    return e;
}

VkPhysicalDeviceFeatures usefulFeatures(VkPhysicalDevice physicalDevice) {
    VkPhysicalDeviceFeatures supported{}, en{};
    if (physicalDevice == VK_NULL_HANDLE) return en;
    vkGetPhysicalDeviceFeatures(physicalDevice, &supported);
    en.geometryShader = supported.geometryShader;
    en.depthClamp = supported.depthClamp;
    en.samplerAnisotropy = supported.samplerAnisotropy;
    en.independentBlend = supported.independentBlend;
    en.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
    en.vertexPipelineStoresAndAtomics = supported.vertexPipelineStoresAndAtomics;
    en.shaderStorageImageExtendedFormats = supported.shaderStorageImageExtendedFormats;
    en.shaderStorageImageWriteWithoutFormat = supported.shaderStorageImageWriteWithoutFormat;
    en.shaderStorageImageReadWithoutFormat = supported.shaderStorageImageReadWithoutFormat;
    en.largePoints = supported.largePoints;
    return en;
}

namespace {
VulkanDevice* asVulkan(rhi::IDevice& device) { return dynamic_cast<VulkanDevice*>(&device); }
}  // namespace

void setCommandBuffer(rhi::IDevice& device, VkCommandBuffer commandBuffer) {
    if (auto* d = asVulkan(device)) d->setAppCommandBuffer(commandBuffer);
}
VkDevice nativeDevice(rhi::IDevice& device) {
    auto* d = asVulkan(device);
    return d ? d->device() : VK_NULL_HANDLE;
}
VkPhysicalDevice nativePhysicalDevice(rhi::IDevice& device) {
    auto* d = asVulkan(device);
    return d ? d->physicalDevice() : VK_NULL_HANDLE;
}
VkInstance nativeInstance(rhi::IDevice& device) {
    auto* d = asVulkan(device);
    return d ? d->instance() : VK_NULL_HANDLE;
}
VkQueue nativeQueue(rhi::IDevice& device) {
    auto* d = asVulkan(device);
    return d ? d->queue() : VK_NULL_HANDLE;
}
uint32_t nativeQueueFamily(rhi::IDevice& device) {
    auto* d = asVulkan(device);
    return d ? d->queueFamily() : 0;
}
VkImage nativeImage(rhi::IDevice& device, rhi::TextureHandle texture) {
    auto* d = asVulkan(device);
    return d ? d->nativeImage(texture) : VK_NULL_HANDLE;
}
VkBuffer nativeBuffer(rhi::IDevice& device, rhi::BufferHandle buffer) {
    auto* d = asVulkan(device);
    return d ? d->nativeBuffer(buffer) : VK_NULL_HANDLE;
}
std::optional<uint64_t> barrierCount(rhi::IDevice& device) {
    auto* d = asVulkan(device);
    return d ? std::optional(d->barrierCount()) : std::nullopt;
}
std::optional<uint64_t> pipelineBarrierCount(rhi::IDevice& device) {
    auto* d = asVulkan(device);
    return d ? std::optional(d->pipelineBarrierCount()) : std::nullopt;
}
std::optional<uint64_t> validationMessageCount(rhi::IDevice& device) {
    auto* d = asVulkan(device);
    return d ? std::optional(d->validationMessages()) : std::nullopt;
}
std::optional<bool> usesPushDescriptors(rhi::IDevice& device) {
    auto* d = asVulkan(device);
    return d ? std::optional(d->pushDescriptors()) : std::nullopt;
}

}  // namespace bricklight::vulkan
