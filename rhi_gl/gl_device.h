// The GL 4.5 IDevice. Its methods are split by concept over gl_device.cpp (creation, diagnostics,
// markers, frames), gl_resources.cpp, gl_transfers.cpp, gl_bindings.cpp, gl_compute.cpp and gl_draw.cpp.
//
// Every public call first validates everything it can (handles, ranges, usages, formats, reflection),
// reporting "<call> '<label>': <field>: <problem>" and returning false with nothing changed; only then
// does it touch GL.
#pragma once

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "bricklight/rhi_gl.h"
#include "gl_barriers.h"
#include "gl_constants.h"
#include "gl_draw_state.h"
#include "gl_functions.h"
#include "gl_objects.h"
#include "gl_programs.h"
#include "gl_timing.h"
#include "gl_views.h"

namespace bricklight::gl::detail {

// Names the call in messages: "dispatch 'blur': storageImages[0] (slot 2): ...".
struct Call {
    const char* name;
    const char* label = nullptr;
    std::string prefix() const {
        return std::string(name) + (label && *label ? std::string(" '") + label + "'" : std::string());
    }
};

// The union of the bindings the stages of one call declare, by (class, slot).
struct Declared {
    const rhi::ReflectedBinding* at[5][16] = {};
    std::string shaderNames;
};

// What a validated Bindings turns into: GL binding calls to make, barrier bits the consumers need, and
// the resources whose incoherent writes must be recorded after the call.
struct BindingPlan {
    struct Constants { GLuint index; const void* data; uint32_t size, bindSize; };
    struct Texture { GLuint unit, texture, sampler; };
    struct Buffer { GLuint index, buffer; GLintptr offset; GLsizeiptr size; };
    struct Image { GLuint unit, texture; GLint level; GLboolean layered; GLint layer; GLenum access, format; };
    std::vector<Constants> constants;
    std::vector<Texture> textures;
    std::vector<Buffer> buffers;
    std::vector<Image> images;
    GLbitfield barriers = 0;
    std::vector<TextureRecord*> writtenTextures;
    std::vector<BufferRecord*> writtenBuffers;
};

class Device final : public rhi::IDevice {
public:
    static std::unique_ptr<Device> create(const DeviceOptions& options, std::unique_ptr<HeadlessContext> owned);
    ~Device() override;

    const rhi::Capabilities& capabilities() const override { return caps_; }
    void setErrorCallback(rhi::ErrorCallback callback) override { callback_ = std::move(callback); }

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

    bool dispatch(const rhi::DispatchState& state, uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ) override;
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

    uint64_t barrierCount() const { return barriers_.count(); }
    void onDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity, const char* message);

private:
    Device() = default;
    bool init(const DeviceOptions& options, std::string* error);
    void queryCapabilities();
    void makeCurrent() const;  // owned headless context: make it current if another one took over

    // Diagnostics.
    void report(rhi::Severity severity, const std::string& message) const;
    bool fail(const Call& call, const std::string& message) const;  // reports an error, returns false

    // Lookups: report "<field>: null/destroyed/unknown <kind> handle" and return null.
    TextureRecord* texture(rhi::TextureHandle h, const Call& call, const std::string& field);
    BufferRecord* buffer(rhi::BufferHandle h, const Call& call, const std::string& field);
    SamplerRecord* sampler(rhi::SamplerHandle h, const Call& call, const std::string& field);
    ShaderRecord* shader(rhi::ShaderHandle h, const Call& call, const std::string& field);
    std::string missingHandle(const char* kind, uint32_t id) const;
    uint32_t newId() { return nextId_++; }

    // Resources (gl_resources.cpp).
    bool checkTextureDesc(const Call& call, const rhi::TextureDesc& desc) const;
    bool checkBufferDesc(const Call& call, const rhi::BufferDesc& desc) const;
    bool uploadTexture(const TextureRecord& t, uint32_t mip, uint32_t layer, uint32_t layers, const void* data);

    // Transfers (gl_transfers.cpp).
    bool checkSubresource(const Call& call, const std::string& field, const TextureRecord& t,
                          const rhi::TextureSubresource& sub) const;
    bool checkBufferRange(const Call& call, const std::string& field, const BufferRecord& b, uint64_t offset,
                          uint64_t size) const;
    void setPixelStore();

    // Bindings (gl_bindings.cpp).
    bool resolveView(const Call& call, const std::string& field, const TextureRecord& t, const rhi::TextureView& view,
                     ResolvedView* out) const;
    bool declare(const Call& call, const ShaderRecord& shader, Declared* declared) const;
    bool resolveBindings(const Call& call, const rhi::Bindings& bindings, const Declared& declared, uint32_t flags,
                         BindingPlan* plan);
    void applyBindings(const BindingPlan& plan);
    void finishBindings(const BindingPlan& plan);  // records writes, unbinds image units
    void pushLabel(const char* label);
    void popLabel(const char* label);

    // Draws (gl_draw.cpp).
    enum class DrawKind { Direct, Indexed, Indirect, IndirectIndexed };
    struct DrawPlan;
    bool drawImpl(const Call& call, const rhi::DrawCallState& state, DrawKind kind, const void* args,
                  rhi::BufferHandle argsBuffer, uint64_t argsOffset);
    bool prepareDraw(const Call& call, const rhi::DrawCallState& state, DrawKind kind, DrawPlan* plan);
    bool prepareTargets(const Call& call, const rhi::DrawCallState& state, DrawPlan* plan);
    void clearTargets(const rhi::DrawCallState& state, const DrawPlan& plan);

    // Dispatch (gl_compute.cpp).
    bool prepareDispatch(const Call& call, const rhi::DispatchState& state, ShaderRecord** shader, BindingPlan* plan);

    std::unique_ptr<HeadlessContext> ownedContext_;  // first member: destroyed last, after the GL cleanup
    Functions gl;
    rhi::ErrorCallback callback_;
    rhi::Capabilities caps_;
    bool debugOutput_ = false;
    bool anisotropy_ = false;
    float maxAnisotropy_ = 1.0f;
    GLint storageAlignment_ = 1;
    // The most one buffer or texture may hold, checked by the backend itself (not left to the validation
    // wrapper): the GPU's memory where the driver tells (GL_NVX_gpu_memory_info), else the host's physical
    // memory (all a software renderer such as llvmpipe has), and never more than GLsizeiptr holds.
    uint64_t maxResourceBytes_ = 0;

    uint32_t nextId_ = 1;
    std::unordered_map<uint32_t, TextureRecord> textures_;
    std::unordered_map<uint32_t, BufferRecord> buffers_;
    std::unordered_map<uint32_t, SamplerRecord> samplers_;
    std::unordered_map<uint32_t, ShaderRecord> shaders_;
    std::unordered_map<uint32_t, std::string> destroyed_;  // id -> "texture 'name'" for messages

    BarrierTracker barriers_;
    ViewCache views_;
    ProgramCache programs_;
    FramebufferCache framebuffers_;
    VertexArrayCache vertexArrays_;
    ConstantRing constants_;
    GLuint scratchIndexBuffer_ = 0;  // indexed drawIndirect with a non-zero index buffer offset
    uint64_t scratchIndexSize_ = 0;

    // Non-blocking read-backs: a copy into a staging buffer followed by a fence.
    struct PendingReadback {
        GLuint buffer = 0;
        GLsync fence = nullptr;
        uint64_t size = 0;
    };
    std::unordered_map<uint64_t, PendingReadback> readbacks_;
    uint64_t nextReadbackTicket_ = 1;
    // Frames in flight, as on Vulkan: endFrame() fences each frame and waits for the one two frames back,
    // which bounds how far the CPU runs ahead and when a read-back is at the latest ready.
    static constexpr size_t kFramesInFlight = 2;
    GLsync frameFences_[kFramesInFlight] = {};

    MarkerTimer timer_;
    struct Marker {
        std::string path;  // labels of the enclosing markers joined with '/'
        bool timed = false;
        size_t timerIndex = 0;
    };
    std::vector<Marker> markers_;
    uint64_t refusedMarkers_ = 0;  // beginMarker calls beyond rhi::kMaxMarkerDepth still open
    bool timingEnabled_ = false;
    uint32_t timingDepth_ = UINT32_MAX;  // setTimingDepth
    uint64_t frame_ = 0;
};

}  // namespace bricklight::gl::detail
