// The Vulkan IDevice. One class; its members are implemented by concept in vk_*.cpp:
//   vk_setup.cpp      instance, physical device, device, capabilities, debug messenger, factories
//   vk_memory.cpp     memory types, buffer/image allocation, the per-frame upload ring
//   vk_resources.cpp  create/destroy/describe/wrap, handle lookup
//   vk_views.cpp      image view cache
//   vk_pipelines.cpp  descriptor set layouts from reflection, pipeline layouts, pipeline cache
//   vk_bindings.cpp   record bindings -> descriptors + declared accesses
//   vk_tracking.cpp   declared accesses -> barriers (rules in vk_barriers.h)
//   vk_commands.cpp   dispatch / draw
//   vk_transfers.cpp  write/copy/clear/read
//   vk_frames.cpp     command buffers, submission, frames in flight, deferred destruction, markers, timing
#pragma once

#include <vulkan/vulkan.h>

#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "bricklight/rhi.h"
#include "bricklight/rhi_vulkan.h"
#include "vk_barriers.h"

namespace bricklight::vulkan::detail {

constexpr uint32_t kFramesInFlight = 2;
constexpr uint32_t kQueriesPerFrame = 512;

// Shared with the debug messenger, which outlives no device but is created before it.
struct Reporter {
    rhi::ErrorCallback callback;
    uint64_t validationMessages = 0;
    void report(rhi::Severity severity, const std::string& message) const;
};

struct ViewKey {
    VkFormat format;
    VkImageViewType type;
    VkImageUsageFlags usage;
    uint32_t baseMip, mipCount, baseLayer, layerCount;
    bool operator==(const ViewKey& o) const {
        return format == o.format && type == o.type && usage == o.usage && baseMip == o.baseMip &&
               mipCount == o.mipCount && baseLayer == o.baseLayer && layerCount == o.layerCount;
    }
};

struct Buffer {
    uint32_t id = 0;
    rhi::BufferDesc desc;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    bool wrapped = false;
    AccessState state;
};

struct Texture {
    uint32_t id = 0;
    rhi::TextureDesc desc;
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    uint32_t layers = 1;  // array layers of the VkImage (3D: 1)
    bool wrapped = false;
    VkImageLayout nativeLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // wrapped: returned to after each call
    std::vector<AccessState> subresources;  // mip * layers + layer
    std::vector<std::pair<ViewKey, VkImageView>> views;
    AccessState& sub(uint32_t mip, uint32_t layer) { return subresources[mip * layers + layer]; }
};

struct Sampler {
    uint32_t id = 0;
    rhi::SamplerDesc desc;
    VkSampler sampler = VK_NULL_HANDLE;
};

struct Shader {
    uint32_t id = 0;
    std::string name;
    const rhi::ShaderBlob* blob = nullptr;
    VkShaderModule module = VK_NULL_HANDLE;
};

// One binding of set 0 as the shaders of a call declare it.
struct ProgramBinding {
    uint32_t binding = 0;
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
    VkShaderStageFlags stages = 0;
    VkPipelineStageFlags2 pipelineStages = 0;
    rhi::BindingClass cls = rhi::BindingClass::Constants;
    uint8_t slot = 0;
    const rhi::ReflectedBinding* reflection = nullptr;
};

struct SetLayout {
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    bool push = false;
};

// The shaders of one call and what they declare.
struct Program {
    std::vector<uint32_t> shaderIds;
    std::vector<ProgramBinding> bindings;
    const SetLayout* layout = nullptr;
};

struct PipelineEntry {
    VkPipeline pipeline = VK_NULL_HANDLE;
    std::vector<uint32_t> shaderIds;
};

// What one call will do, fully checked before anything is recorded.
struct CallPlan {
    struct Descriptor {
        uint32_t binding;
        VkDescriptorType type;
        VkDescriptorBufferInfo buffer;
        VkDescriptorImageInfo image;
        const void* constantsData = nullptr;  // constants: copied into the upload ring at record time
        uint32_t constantsSize = 0;
        uint32_t constantsRange = 0;
    };
    std::vector<Descriptor> descriptors;
    struct BufferUse {
        Buffer* buffer;
        AccessRequest request;
    };
    struct TextureUse {
        Texture* texture;
        uint32_t mip, layer;
        AccessRequest request;
    };
    std::vector<BufferUse> buffers;
    std::vector<TextureUse> textures;  // one per subresource
};

struct UploadChunk {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    uint8_t* mapped = nullptr;
    VkDeviceSize size = 0;
    VkDeviceSize used = 0;
};

struct UploadAllocation {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    uint8_t* mapped = nullptr;
};

struct FrameSlot {
    VkCommandPool pool = VK_NULL_HANDLE;
    std::vector<VkCommandBuffer> commandBuffers;
    size_t nextCommandBuffer = 0;
    VkFence fence = VK_NULL_HANDLE;
    bool pending = false;  // fence submitted, not yet recycled
    uint64_t serial = 0;
    std::vector<UploadChunk> chunks;
    std::vector<VkDescriptorPool> descriptorPools;
    size_t currentDescriptorPool = 0;
    VkQueryPool queryPool = VK_NULL_HANDLE;
    uint32_t queriesUsed = 0;
    struct TimedMarker {
        std::string label;
        uint32_t beginQuery, endQuery;
    };
    std::vector<TimedMarker> timed;
    std::vector<std::function<void()>> garbage;
};

class VulkanDevice final : public rhi::IDevice {
public:
    static std::unique_ptr<VulkanDevice> createStandalone(const DeviceOptions& options);
    static std::unique_ptr<VulkanDevice> createEmbedded(const EmbeddedDesc& desc);
    ~VulkanDevice() override;

    const rhi::Capabilities& capabilities() const override { return caps_; }
    void setErrorCallback(rhi::ErrorCallback callback) override { reporter_->callback = std::move(callback); }

    rhi::TextureHandle createTexture(const rhi::TextureDesc& desc, const void* initialData) override;
    rhi::BufferHandle createBuffer(const rhi::BufferDesc& desc, const void* initialData) override;
    rhi::SamplerHandle createSampler(const rhi::SamplerDesc& desc) override;
    rhi::ShaderHandle createShader(const rhi::ShaderDesc& desc) override;
    rhi::TextureHandle wrapNativeTexture(const rhi::TextureDesc& desc, rhi::NativeObject native) override;
    rhi::BufferHandle wrapNativeBuffer(const rhi::BufferDesc& desc, rhi::NativeObject native) override;
    void destroy(rhi::TextureHandle texture) override;
    void destroy(rhi::BufferHandle buffer) override;
    void destroy(rhi::SamplerHandle sampler) override;
    void destroy(rhi::ShaderHandle shader) override;
    const rhi::TextureDesc* describe(rhi::TextureHandle texture) const override;
    const rhi::BufferDesc* describe(rhi::BufferHandle buffer) const override;

    bool writeBuffer(rhi::BufferHandle buffer, uint64_t offset, const void* data, uint64_t size) override;
    bool writeTexture(rhi::TextureHandle texture, rhi::TextureSubresource sub, const void* data) override;
    bool copyBuffer(rhi::BufferHandle dst, uint64_t dstOffset, rhi::BufferHandle src, uint64_t srcOffset,
                    uint64_t size) override;
    bool copyTexture(rhi::TextureHandle dst, rhi::TextureSubresource dstSub, rhi::TextureHandle src,
                     rhi::TextureSubresource srcSub) override;
    bool clearBuffer(rhi::BufferHandle buffer, rhi::BufferRange range, uint32_t value) override;
    bool clearTexture(rhi::TextureHandle texture, uint32_t baseMip, uint32_t mipCount, rhi::ClearValue value) override;
    bool readBuffer(rhi::BufferHandle buffer, uint64_t offset, uint64_t size, void* out) override;
    bool readTexture(rhi::TextureHandle texture, rhi::TextureSubresource sub, void* out) override;
    uint64_t requestReadback(rhi::BufferHandle buffer, uint64_t offset, uint64_t size) override;
    rhi::ReadbackStatus pollReadback(uint64_t ticket, void* out) override;

    bool dispatch(const rhi::DispatchState& state, uint32_t x, uint32_t y, uint32_t z) override;
    bool dispatchIndirect(const rhi::DispatchState& state, rhi::BufferHandle args, uint64_t offset) override;
    bool draw(const rhi::DrawCallState& state, const rhi::DrawArgs& args) override;
    bool drawIndexed(const rhi::DrawCallState& state, const rhi::DrawIndexedArgs& args) override;
    bool drawIndirect(const rhi::DrawCallState& state, rhi::BufferHandle args, uint64_t offset, bool indexed) override;

    void beginMarker(const char* label) override;
    void endMarker() override;
    void setTimingEnabled(bool enabled) override { timingEnabled_ = enabled && caps_.timestamps; }
    void setTimingDepth(uint32_t depth) override { timingDepth_ = depth ? depth : 1; }
    std::vector<rhi::MarkerTiming> takeTimings() override;
    void endFrame() override;
    void waitIdle() override;

    // Native access (rhi_vulkan.h).
    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physical_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }
    void setAppCommandBuffer(VkCommandBuffer commandBuffer);
    uint64_t barrierCount() const { return barrierCount_; }
    uint64_t pipelineBarrierCount() const { return pipelineBarriers_; }
    uint64_t validationMessages() const { return reporter_->validationMessages; }
    bool pushDescriptors() const { return pushDescriptors_; }
    VkImage nativeImage(rhi::TextureHandle t) const;
    VkBuffer nativeBuffer(rhi::BufferHandle b) const;

private:
    VulkanDevice() = default;

    // vk_setup.cpp
    bool initDevice();  // after instance_/physical_/device_/queue_ are set: caps, functions, frames
    void queryCapabilities();
    void loadFunctions();

    // errors
    bool fail(const std::string& message) const;
    void warn(const std::string& message) const;
    static std::string quoted(const char* label);

    // vk_memory.cpp
    uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) const;
    bool allocateBuffer(VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags required,
                        VkMemoryPropertyFlags preferred, VkBuffer* buffer, VkDeviceMemory* memory, void** mapped);
    bool allocateImageMemory(VkImage image, VkDeviceMemory* memory);
    UploadAllocation allocateUpload(VkDeviceSize size, VkDeviceSize alignment);
    void releaseUploads(FrameSlot& slot);
    void setName(VkObjectType type, uint64_t handle, const std::string& name) const;

    // vk_resources.cpp
    Texture* findTexture(rhi::TextureHandle h, const std::string& call, const char* what);
    Buffer* findBuffer(rhi::BufferHandle h, const std::string& call, const char* what);
    Sampler* findSampler(rhi::SamplerHandle h, const std::string& call, const char* what);
    Shader* findShader(rhi::ShaderHandle h, const std::string& call, const char* what);
    std::string textureName(const Texture& t) const;
    std::string bufferName(const Buffer& b) const;
    bool checkTextureDesc(const rhi::TextureDesc& desc, const std::string& call);
    // Whether `bytes` of memory can be one allocation on this device (reports the refusal).
    bool checkAllocationSize(uint64_t bytes, const std::string& call, const char* what);
    bool checkBufferSize(const rhi::BufferDesc& desc, const std::string& call);
    Texture* addTexture(const rhi::TextureDesc& desc, VkImage image, VkDeviceMemory memory, bool wrapped);
    void uploadInitialTexture(Texture& texture, const void* data);

    // vk_views.cpp
    VkImageView getView(Texture& texture, const ViewKey& key);

    // vk_pipelines.cpp
    const Program* getProgram(const std::vector<Shader*>& shaders, const std::string& call);
    const SetLayout* getSetLayout(const std::vector<ProgramBinding>& bindings);
    VkPipeline getComputePipeline(const Program& program, Shader& shader, const std::string& call);
    VkPipeline getGraphicsPipeline(const Program& program, const rhi::DrawCallState& state, Shader* vs, Shader* gs,
                                   Shader* fs, const std::string& call);
    void forgetShader(uint32_t shaderId);

    // vk_bindings.cpp
    bool planBindings(const Program& program, const rhi::Bindings& bindings, uint32_t flags, const std::string& call,
                      CallPlan& plan);
    bool addTextureUse(CallPlan& plan, Texture& texture, uint32_t baseMip, uint32_t mipCount, uint32_t baseLayer,
                       uint32_t layerCount, const AccessRequest& request, const std::string& call,
                       const std::string& what);
    void addBufferUse(CallPlan& plan, Buffer& buffer, const AccessRequest& request);
    bool bindDescriptors(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint, const Program& program, CallPlan& plan);
    VkDescriptorSet allocateDescriptorSet(VkDescriptorSetLayout layout);

    // vk_tracking.cpp
    void recordBarriers(VkCommandBuffer cmd, const CallPlan& plan);
    void releaseWrapped(VkCommandBuffer cmd, const CallPlan& plan);
    void notePending(const AccessRequest& request);

    // vk_commands.cpp
    bool prepareDispatch(const rhi::DispatchState& state, const std::string& call, CallPlan& plan, Shader** shader,
                         const Program** program, VkPipeline* pipeline);
    bool prepareDraw(const rhi::DrawCallState& state, const std::string& call, CallPlan& plan,
                     const Program** program, VkPipeline* pipeline, VkExtent2D* extent);
    bool checkViewport(const rhi::DrawCallState& state, const std::string& call);
    void recordDraw(const rhi::DrawCallState& state, const Program& program, VkPipeline pipeline, VkExtent2D extent,
                    CallPlan& plan, const std::function<void(VkCommandBuffer)>& issue);
    void beginCallLabel(VkCommandBuffer cmd, const char* label);
    void endCallLabel(VkCommandBuffer cmd, const char* label);

    // vk_transfers.cpp
    bool checkSubresource(const Texture& t, rhi::TextureSubresource sub, const std::string& call, uint32_t* layers);
    void copyTextureRegions(VkCommandBuffer cmd, Texture& t, uint32_t mip, uint32_t layer, uint32_t layers,
                            VkBuffer buffer, VkDeviceSize offset, bool toImage, VkDeviceSize* layerStride);
    void trackTransfer(VkCommandBuffer cmd, CallPlan& plan);

    // vk_frames.cpp
    VkCommandBuffer cmd();
    void flushInternal();
    bool waitForGpu();
    void recycle(FrameSlot& slot, bool harvestTimings);
    void releaseTransient(FrameSlot& slot);
    void deferDestroy(std::function<void()> fn);
    FrameSlot& frame() { return frames_[currentFrame_]; }
    void createFrames();
    void destroyFrames();

public:
    std::shared_ptr<Reporter> reporter_ = std::make_shared<Reporter>();

private:
    // Native objects.
    bool ownsDevice_ = false;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    VkPhysicalDeviceProperties props_{};
    VkPhysicalDeviceMemoryProperties memProps_{};
    VkPhysicalDeviceFeatures enabled_{};
    uint32_t timestampValidBits_ = 0;
    bool debugUtils_ = false;
    bool pushDescriptors_ = false;
    uint32_t maxPushDescriptors_ = 0;
    rhi::Capabilities caps_;
    // What one buffer or one allocation may hold here: maintenance4's maxBufferSize, maintenance3's
    // maxMemoryAllocationSize and the largest device-local heap. Checked by the backend itself (not left to the
    // validation wrapper): a size of 2^64-1, rounded up to 4, became 0 and a 4-byte buffer stood for it.
    uint64_t maxBufferBytes_ = 0;
    uint64_t maxAllocationBytes_ = 0;

    // Extension entry points (null when unavailable).
    PFN_vkCmdPushDescriptorSetKHR pushDescriptorSet_ = nullptr;
    PFN_vkSetDebugUtilsObjectNameEXT setObjectName_ = nullptr;
    PFN_vkCmdBeginDebugUtilsLabelEXT beginLabel_ = nullptr;
    PFN_vkCmdEndDebugUtilsLabelEXT endLabel_ = nullptr;
    // BRICKLIGHT_VK_SHADER_STATISTICS=1 with VK_KHR_pipeline_executable_properties: each compute pipeline's
    // driver statistics (registers, ...) are reported as Info messages when it is created.
    PFN_vkGetPipelineExecutablePropertiesKHR executableProperties_ = nullptr;
    PFN_vkGetPipelineExecutableStatisticsKHR executableStatistics_ = nullptr;
    void reportShaderStatistics(VkPipeline pipeline, const std::string& name);

    // Resources. Ids per kind start at 1 and are never reused.
    std::unordered_map<uint32_t, std::unique_ptr<Texture>> textures_;
    std::unordered_map<uint32_t, std::unique_ptr<Buffer>> buffers_;
    std::unordered_map<uint32_t, std::unique_ptr<Sampler>> samplers_;
    std::unordered_map<uint32_t, std::unique_ptr<Shader>> shaders_;
    uint32_t nextTextureId_ = 1, nextBufferId_ = 1, nextSamplerId_ = 1, nextShaderId_ = 1;

    // Caches.
    std::unordered_map<std::string, std::unique_ptr<SetLayout>> setLayouts_;
    std::unordered_map<std::string, std::unique_ptr<Program>> programs_;
    std::unordered_map<std::string, PipelineEntry> pipelines_;

    // Frames and recording.
    FrameSlot frames_[kFramesInFlight];
    uint32_t currentFrame_ = 0;
    uint64_t frameSerial_ = 0;
    VkFence syncFence_ = VK_NULL_HANDLE;
    VkCommandBuffer recording_ = VK_NULL_HANDLE;  // internal command buffer being recorded
    VkCommandBuffer appCommandBuffer_ = VK_NULL_HANDLE;
    uint64_t barrierCount_ = 0;
    uint64_t pipelineBarriers_ = 0;  // vkCmdPipelineBarrier2 calls made by recordBarriers
    // Barrier reuse (vk_barriers.h): calls are numbered, the barriers recorded lately are remembered, and
    // the stages (and writes) used since the last barrier are folded into the next one.
    bool barrierReuse_ = true;
    uint64_t callSerial_ = 0;
    BarrierHistory history_;
    VkPipelineStageFlags2 pendingStages_ = 0;
    VkAccessFlags2 pendingWriteAccess_ = 0;

    // Non-blocking read-backs: a host-visible copy, finished once the frame it was recorded in (serial)
    // has been recycled or a full wait (waitCount_) happened after it.
    struct PendingReadback {
        VkBuffer buffer = VK_NULL_HANDLE;
        VkDeviceMemory memory = VK_NULL_HANDLE;
        void* mapped = nullptr;
        uint64_t size = 0;
        uint64_t serial = 0;
        uint64_t waitCount = 0;
    };
    std::unordered_map<uint64_t, PendingReadback> readbacks_;
    uint64_t nextReadbackTicket_ = 1;
    int64_t completedSerial_ = -1;  // highest frame serial whose fence has signalled
    uint64_t waitCount_ = 0;

    // Markers and timing.
    struct OpenMarker {
        std::string label;  // full, '/'-joined
        int64_t beginQuery = -1;
        uint64_t frame = 0;
        VkCommandBuffer labelCommandBuffer = VK_NULL_HANDLE;  // where its debug label is open
    };
    std::vector<OpenMarker> markers_;
    uint64_t refusedMarkers_ = 0;  // beginMarker calls beyond rhi::kMaxMarkerDepth still open
    bool timingEnabled_ = false;
    uint32_t timingDepth_ = UINT32_MAX;  // setTimingDepth
    std::vector<rhi::MarkerTiming> finishedTimings_;
    bool queryOverflowReported_ = false;
};

}  // namespace bricklight::vulkan::detail
