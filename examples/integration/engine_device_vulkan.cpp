// Vulkan as an engine sets it up: the application owns the instance (with the validation layer and a
// debug messenger when they are installed), the VkDevice, the queue, the command buffers and the frame
// pacing. The objects are made by Bricklight's start-up (vulkan::createVulkanObjects); an engine with its own
// start-up hands its objects over the same way, with what vulkan::usefulFeatures() names enabled. Bricklight's backend is created *embedded* on those objects and records into the application's
// command buffer (vulkan::setCommandBuffer); the application submits it. docs/backend_vulkan.md,
// "Embedded mode", lists the rules this file follows.
#include <array>
#include <cstring>
#include <optional>
#include <vector>

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
        }
        bricklight::vulkan::destroyVulkanObjects(objects_);
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
    bricklight::vulkan::VulkanObjects objects_;
    VkDevice device_ = VK_NULL_HANDLE;  // objects_'s, for short
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::array<VkCommandBuffer, kFramesInFlight> commandBuffers_{};
    std::array<VkFence, kFramesInFlight> fences_{};
    uint32_t slot_ = 0;
    std::unique_ptr<bricklight::rhi::IDevice> backend_;
};

bool VulkanEngineDevice::create(std::string* error) {
    auto fail = [&](const std::string& m) {
        *error = m;
        return false;
    };
    std::shared_ptr<MessageLog> log = messages_;
    bricklight::vulkan::StartupDesc sd;
    sd.applicationName = "bricklight_integration";
    const bool validation = hasLayer("VK_LAYER_KHRONOS_validation");  // on whenever it is installed
    sd.enableValidation = validation;
    sd.errorCallback = [log](Severity s, const std::string& m) { log->add("vulkan", s, m); };
    std::optional<bricklight::vulkan::VulkanObjects> objects = bricklight::vulkan::createVulkanObjects(sd);
    if (!objects) return fail("Vulkan start-up failed (see the messages above)");
    objects_ = std::move(*objects);
    device_ = objects_.device;
    queue_ = objects_.queue;

    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = objects_.queueFamilyIndex;
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
    const bricklight::vulkan::EmbeddedDesc e =
        bricklight::vulkan::embeddedDesc(objects_, [log](Severity s, const std::string& m) { log->add("vulkan backend", s, m); });
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
