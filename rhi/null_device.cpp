// The null device: issues handles and remembers descriptions, executes nothing. With the validation
// wrapper on top, every record check runs on a machine with no GPU and no driver.
#include <cstring>
#include <unordered_map>

#include "bricklight/rhi_validation.h"
#include "size_math.h"

namespace bricklight::rhi {

namespace {

Capabilities defaultCapabilities() {
    Capabilities c;
    c.backendName = "null";
    c.deviceName = "null device";
    Limits& l = c.limits;
    l.maxTextureSize2D = 16384;
    l.maxTextureSize3D = 2048;
    l.maxTextureArrayLayers = 2048;
    for (int i = 0; i < 3; ++i) l.maxComputeGroupCount[i] = 65535;
    l.maxComputeGroupSize[0] = l.maxComputeGroupSize[1] = 1024;
    l.maxComputeGroupSize[2] = 64;
    l.maxComputeGroupInvocations = 1024;
    l.maxComputeSharedMemoryBytes = 32768;
    l.maxStorageBufferRange = 1u << 30;
    l.maxColorTargets = 8;
    l.minStorageBufferOffsetAlignment = 16;
    l.minUniformBufferOffsetAlignment = 256;
    for (size_t f = 1; f < static_cast<size_t>(Format::Count); ++f) {
        Format format = static_cast<Format>(f);
        const FormatInfo& info = formatInfo(format);
        uint32_t bits = FormatSupport::Sampled;
        if (info.kind == FormatInfo::Kind::Depth) {
            bits |= FormatSupport::DepthTarget | FormatSupport::Filterable;
        } else {
            bits |= FormatSupport::RenderTarget;
            if (info.kind != FormatInfo::Kind::Uint && info.kind != FormatInfo::Kind::Sint)
                bits |= FormatSupport::Filterable | FormatSupport::Blendable;
            if (format != Format::RGBA8_SRGB && format != Format::R11G11B10_FLOAT && format != Format::RGB9E5_FLOAT) bits |= FormatSupport::Storage;
            if (format == Format::R32_UINT || format == Format::R32_SINT) bits |= FormatSupport::StorageAtomic;
        }
        c.formatSupport[f] = bits;
    }
    c.geometryShader = true;
    c.timestamps = false;
    return c;
}

class NullDevice final : public IDevice {
public:
    explicit NullDevice(const Capabilities& caps) : caps_(caps) {}

    template <typename Map, typename Desc>
    std::conditional_t<std::is_same_v<Desc, TextureDesc>, TextureHandle, BufferHandle> add(Map& map, const Desc& d) {
        uint32_t id = ++nextId_;
        map[id] = d;
        return {id};
    }

    const Capabilities& capabilities() const override { return caps_; }
    void setErrorCallback(ErrorCallback cb) override { callback_ = std::move(cb); }

    TextureHandle createTexture(const TextureDesc& d, const void*) override { return add(textures_, d); }
    BufferHandle createBuffer(const BufferDesc& d, const void*) override { return add(buffers_, d); }
    SamplerHandle createSampler(const SamplerDesc&) override { return SamplerHandle{++nextId_}; }
    ShaderHandle createShader(const ShaderDesc& d) override {
        if (!d.blob) return {};
        return ShaderHandle{++nextId_};
    }
    TextureHandle wrapNativeTexture(const TextureDesc& d, NativeObject) override { return add(textures_, d); }
    BufferHandle wrapNativeBuffer(const BufferDesc& d, NativeObject) override { return add(buffers_, d); }
    void destroy(TextureHandle h) override { textures_.erase(h.id); }
    void destroy(BufferHandle h) override { buffers_.erase(h.id); }
    void destroy(SamplerHandle) override {}
    void destroy(ShaderHandle) override {}
    const TextureDesc* describe(TextureHandle h) const override {
        auto it = textures_.find(h.id);
        return it == textures_.end() ? nullptr : &it->second;
    }
    const BufferDesc* describe(BufferHandle h) const override {
        auto it = buffers_.find(h.id);
        return it == buffers_.end() ? nullptr : &it->second;
    }

    bool writeBuffer(BufferHandle, uint64_t, const void*, uint64_t) override { return true; }
    bool writeTexture(TextureHandle, TextureSubresource, const void*) override { return true; }
    bool copyBuffer(BufferHandle, uint64_t, BufferHandle, uint64_t, uint64_t) override { return true; }
    bool copyTexture(TextureHandle, TextureSubresource, TextureHandle, TextureSubresource) override { return true; }
    bool clearBuffer(BufferHandle, BufferRange, uint32_t) override { return true; }
    bool clearTexture(TextureHandle, uint32_t, uint32_t, ClearValue) override { return true; }
    bool readBuffer(BufferHandle, uint64_t, uint64_t size, void* out) override {
        if (out) std::memset(out, 0, size);
        return true;
    }
    uint64_t requestReadback(BufferHandle b, uint64_t, uint64_t size) override {
        if (!describe(b)) return 0;
        readbacks_[nextTicket_] = size;
        return nextTicket_++;
    }
    ReadbackStatus pollReadback(uint64_t ticket, void* out) override {
        auto it = readbacks_.find(ticket);
        if (it == readbacks_.end()) return ReadbackStatus::Failed;
        if (out) std::memset(out, 0, it->second);
        readbacks_.erase(it);
        return ReadbackStatus::Ready;
    }
    bool readTexture(TextureHandle t, TextureSubresource sub, void* out) override {
        const TextureDesc* d = describe(t);
        if (!d) return false;
        // The one check the null device makes: it writes `out`, and a subresource outside the texture has no
        // size to write (the count would shift by 32 or more, or overflow).
        const auto bytes = sizes::subresourceBytes(*d, sub);
        if (!bytes) {
            if (callback_) callback_(Severity::Error, "readTexture: subresource outside texture '" + d->debugName + "'");
            return false;
        }
        if (out) std::memset(out, 0, *bytes);
        return true;
    }
    bool dispatch(const DispatchState&, uint32_t, uint32_t, uint32_t) override { return ++calls_, true; }
    bool dispatchIndirect(const DispatchState&, BufferHandle, uint64_t) override { return ++calls_, true; }
    bool draw(const DrawCallState&, const DrawArgs&) override { return ++calls_, true; }
    bool drawIndexed(const DrawCallState&, const DrawIndexedArgs&) override { return ++calls_, true; }
    bool drawIndirect(const DrawCallState&, BufferHandle, uint64_t, bool) override { return ++calls_, true; }
    void beginMarker(const char*) override {}
    void endMarker() override {}
    void setTimingEnabled(bool) override {}
    void setTimingDepth(uint32_t) override {}
    std::vector<MarkerTiming> takeTimings() override { return {}; }
    void endFrame() override {}
    void waitIdle() override {}

private:
    std::unordered_map<uint64_t, uint64_t> readbacks_;  // ticket -> size
    uint64_t nextTicket_ = 1;

    Capabilities caps_;
    ErrorCallback callback_;
    uint32_t nextId_ = 0;
    uint64_t calls_ = 0;
    std::unordered_map<uint32_t, TextureDesc> textures_;
    std::unordered_map<uint32_t, BufferDesc> buffers_;
};

}  // namespace

std::unique_ptr<IDevice> createNullDevice(const Capabilities* capabilities) {
    return std::make_unique<NullDevice>(capabilities ? *capabilities : defaultCapabilities());
}

}  // namespace bricklight::rhi
