// Vulkan reference backend of the stateless RHI (docs/backend_vulkan.md).
// Standalone: the backend owns instance, device and queue. Embedded: the application owns them and the
// backend records into the application's command buffers when asked to (setCommandBuffer).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bricklight/rhi.h"

namespace bricklight::vulkan {

struct DeviceOptions {
    // VK_LAYER_KHRONOS_validation + a VK_EXT_debug_utils messenger; every validation message (warning or
    // error) goes to errorCallback as Severity::Error prefixed "vulkan validation: ".
    // Also on when the environment has BRICKLIGHT_VK_VALIDATION=1. BRICKLIGHT_VK_SYNC_VALIDATION=1 adds
    // synchronization validation (off by default: it reports the write-after-write overlap that
    // DispatchFlags::NoBarrierWithPreviousWriter asks for on purpose).
    bool enableValidation = false;
    bool enableSyncValidation = false;
    bool preferSoftware = false;       // pick lavapipe/CPU even if a GPU exists
    std::string deviceNameContains;    // optional filter; env BRICKLIGHT_VK_DEVICE overrides
    // Test hook: use per-frame descriptor pools even when VK_KHR_push_descriptor is available
    // (also env BRICKLIGHT_VK_NO_PUSH_DESCRIPTORS=1).
    bool disablePushDescriptors = false;
    // Emit every hazard's barrier even when an earlier barrier already ordered it, and fold nothing
    // outstanding into a barrier (the behaviour before barrier reuse; for A/B timing and tests; also env
    // BRICKLIGHT_VK_NO_BARRIER_REUSE=1).
    bool disableBarrierReuse = false;
    rhi::ErrorCallback errorCallback;  // if empty, errors go to stderr
};

// Standalone device; nullptr on failure (the reason goes to the callback, or stderr).
std::unique_ptr<rhi::IDevice> createDevice(const DeviceOptions& options);

// Bricklight's Vulkan start-up for an application that owns the objects and embeds Bricklight on them
// (createEmbeddedDevice below): the instance (with the validation layer and a debug messenger when asked), the
// window's surface when asked, the physical device, one graphics+compute queue (that can present to the surface)
// and the device, with the features and extensions Bricklight uses. The standalone device starts the same way.
struct StartupDesc {
    const char* applicationName = "bricklight";
    bool enableValidation = false;      // as DeviceOptions (also env BRICKLIGHT_VK_VALIDATION=1)
    bool enableSyncValidation = false;  // (also env BRICKLIGHT_VK_SYNC_VALIDATION=1)
    bool preferSoftware = false;
    std::string deviceNameContains;     // env BRICKLIGHT_VK_DEVICE overrides
    bool disablePushDescriptors = false;
    std::vector<const char*> instanceExtensions;  // the application's own, e.g. glfwGetRequiredInstanceExtensions()
    std::vector<const char*> deviceExtensions;    // e.g. VK_KHR_SWAPCHAIN_EXTENSION_NAME; a device without one is passed over
    // Called once the instance exists, e.g. glfwCreateWindowSurface; the queue must then present to the surface.
    std::function<VkResult(VkInstance, VkSurfaceKHR*)> createSurface;
    rhi::ErrorCallback errorCallback;   // the start-up's failures and the validation messages; empty: stderr
};

// What createVulkanObjects made, the application's to use and to destroy (destroyVulkanObjects) once everything
// made on the device is gone.
struct VulkanObjects {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamilyIndex = 0;
    VkPhysicalDeviceFeatures enabledFeatures{};
    bool pushDescriptorEnabled = false, debugUtilsEnabled = false, validationEnabled = false;
    std::shared_ptr<void> messengerTarget;  // what the debug messenger reports to: kept alive with the objects
};
// Empty on failure, having reported why and destroyed what it made.
std::optional<VulkanObjects> createVulkanObjects(const StartupDesc& desc);
void destroyVulkanObjects(VulkanObjects& objects);  // safe on partly made or empty objects; leaves them empty

// The application's objects. The device must be Vulkan 1.3 with synchronization2 and dynamicRendering
// enabled; the queue must support graphics and compute. The optional fields say what else the
// application enabled (the backend cannot query enabled features): leave them empty/false if unsure.
struct EmbeddedDesc {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamilyIndex = 0;
    rhi::ErrorCallback errorCallback;
    const VkPhysicalDeviceFeatures* enabledFeatures = nullptr;  // geometryShader, depthClamp, ...
    bool pushDescriptorEnabled = false;  // VK_KHR_push_descriptor enabled on the device
    bool debugUtilsEnabled = false;      // VK_EXT_debug_utils enabled on the instance
};
std::unique_ptr<rhi::IDevice> createEmbeddedDevice(const EmbeddedDesc& desc);
// The EmbeddedDesc of objects made by createVulkanObjects (`enabledFeatures` points into `objects`).
EmbeddedDesc embeddedDesc(const VulkanObjects& objects, rhi::ErrorCallback errorCallback);
// The core features the backend can use (geometry shaders, depth clamp, stores and atomics in every stage,
// storage image formats, ...) that `physicalDevice` supports: what the standalone device enables. Enable
// them on an application-owned device and pass them as EmbeddedDesc::enabledFeatures, so that the
// embedded backend offers what the standalone one does.
VkPhysicalDeviceFeatures usefulFeatures(VkPhysicalDevice physicalDevice);

// Embedded mode: record into the application's command buffer (recording state, outside any render
// pass); until the next call all work goes there and the application submits it to desc.queue, then
// calls endFrame(). VK_NULL_HANDLE returns to the backend's own command buffers. Read-backs are refused
// while an application command buffer is set. Also valid on a standalone device.
void setCommandBuffer(rhi::IDevice& device, VkCommandBuffer commandBuffer);

VkDevice nativeDevice(rhi::IDevice& device);
VkPhysicalDevice nativePhysicalDevice(rhi::IDevice& device);
VkInstance nativeInstance(rhi::IDevice& device);
VkQueue nativeQueue(rhi::IDevice& device);
uint32_t nativeQueueFamily(rhi::IDevice& device);
// The VkImage / VkBuffer behind a handle (VK_NULL_HANDLE if not live).
VkImage nativeImage(rhi::IDevice& device, rhi::TextureHandle texture);
VkBuffer nativeBuffer(rhi::IDevice& device, rhi::BufferHandle buffer);

// Counters and state for tests and tools. Each one is empty for a device that is not this backend's own
// (e.g. one under the validation wrapper, or an application's device that forwards to ours): ask the
// backend's device itself. Empty means "this device cannot tell", never "none".
//
// Number of barrier structures (buffer + image + memory) recorded so far; tests use it to check that
// read-after-read and similar sequences emit none.
std::optional<uint64_t> barrierCount(rhi::IDevice& device);
// Number of vkCmdPipelineBarrier2 calls the device's own calls recorded (each waits for the work before it
// in its source stages, so this is how many times the GPU may drain between calls).
std::optional<uint64_t> pipelineBarrierCount(rhi::IDevice& device);
// Number of validation-layer messages received so far (all severities reported).
std::optional<uint64_t> validationMessageCount(rhi::IDevice& device);
// True when descriptors are pushed (VK_KHR_push_descriptor), false when per-frame pools are used.
std::optional<bool> usesPushDescriptors(rhi::IDevice& device);

}  // namespace bricklight::vulkan
