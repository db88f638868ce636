// A device of "an engine's own RHI": an rhi::IDevice that hands every call to another device. An engine's
// adapter would translate each record to its own API here; this one forwards to one of our backends, which
// is the shape an adapter has before it translates anything, and it is not a device the backends know:
// vulkan::barrierCount(forwarder) cannot tell, so the hooks report "unsupported" rather than 0.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "bricklight/rhi.h"

namespace example {

namespace rhi = bricklight::rhi;

class ForwardingDevice final : public rhi::IDevice {
public:
    explicit ForwardingDevice(std::unique_ptr<rhi::IDevice> inner) : inner_(std::move(inner)) {}

    // The device every call goes to (e.g. to ask the backend for its barrier count).
    rhi::IDevice& inner() { return *inner_; }

    const rhi::Capabilities& capabilities() const override { return inner_->capabilities(); }
    void setErrorCallback(rhi::ErrorCallback callback) override { inner_->setErrorCallback(std::move(callback)); }

    rhi::TextureHandle createTexture(const rhi::TextureDesc& desc, const void* initialData) override {
        return inner_->createTexture(desc, initialData);
    }
    rhi::BufferHandle createBuffer(const rhi::BufferDesc& desc, const void* initialData) override {
        return inner_->createBuffer(desc, initialData);
    }
    rhi::SamplerHandle createSampler(const rhi::SamplerDesc& desc) override { return inner_->createSampler(desc); }
    rhi::ShaderHandle createShader(const rhi::ShaderDesc& desc) override { return inner_->createShader(desc); }
    rhi::TextureHandle wrapNativeTexture(const rhi::TextureDesc& desc, rhi::NativeObject native) override {
        return inner_->wrapNativeTexture(desc, native);
    }
    rhi::BufferHandle wrapNativeBuffer(const rhi::BufferDesc& desc, rhi::NativeObject native) override {
        return inner_->wrapNativeBuffer(desc, native);
    }
    void destroy(rhi::TextureHandle texture) override { inner_->destroy(texture); }
    void destroy(rhi::BufferHandle buffer) override { inner_->destroy(buffer); }
    void destroy(rhi::SamplerHandle sampler) override { inner_->destroy(sampler); }
    void destroy(rhi::ShaderHandle shader) override { inner_->destroy(shader); }
    const rhi::TextureDesc* describe(rhi::TextureHandle texture) const override { return inner_->describe(texture); }
    const rhi::BufferDesc* describe(rhi::BufferHandle buffer) const override { return inner_->describe(buffer); }

    bool writeBuffer(rhi::BufferHandle buffer, uint64_t offset, const void* data, uint64_t size) override {
        return inner_->writeBuffer(buffer, offset, data, size);
    }
    bool writeTexture(rhi::TextureHandle texture, rhi::TextureSubresource sub, const void* data) override {
        return inner_->writeTexture(texture, sub, data);
    }
    bool copyBuffer(rhi::BufferHandle dst, uint64_t dstOffset, rhi::BufferHandle src, uint64_t srcOffset,
                    uint64_t size) override {
        return inner_->copyBuffer(dst, dstOffset, src, srcOffset, size);
    }
    bool copyTexture(rhi::TextureHandle dst, rhi::TextureSubresource dstSub, rhi::TextureHandle src,
                     rhi::TextureSubresource srcSub) override {
        return inner_->copyTexture(dst, dstSub, src, srcSub);
    }
    bool clearBuffer(rhi::BufferHandle buffer, rhi::BufferRange range, uint32_t value) override {
        return inner_->clearBuffer(buffer, range, value);
    }
    bool clearTexture(rhi::TextureHandle texture, uint32_t baseMip, uint32_t mipCount, rhi::ClearValue value) override {
        return inner_->clearTexture(texture, baseMip, mipCount, value);
    }
    bool readBuffer(rhi::BufferHandle buffer, uint64_t offset, uint64_t size, void* out) override {
        return inner_->readBuffer(buffer, offset, size, out);
    }
    bool readTexture(rhi::TextureHandle texture, rhi::TextureSubresource sub, void* out) override {
        return inner_->readTexture(texture, sub, out);
    }
    uint64_t requestReadback(rhi::BufferHandle buffer, uint64_t offset, uint64_t size) override {
        return inner_->requestReadback(buffer, offset, size);
    }
    rhi::ReadbackStatus pollReadback(uint64_t ticket, void* out) override { return inner_->pollReadback(ticket, out); }

    bool dispatch(const rhi::DispatchState& state, uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ) override {
        return inner_->dispatch(state, groupsX, groupsY, groupsZ);
    }
    bool dispatchIndirect(const rhi::DispatchState& state, rhi::BufferHandle args, uint64_t offset) override {
        return inner_->dispatchIndirect(state, args, offset);
    }
    bool draw(const rhi::DrawCallState& state, const rhi::DrawArgs& args) override { return inner_->draw(state, args); }
    bool drawIndexed(const rhi::DrawCallState& state, const rhi::DrawIndexedArgs& args) override {
        return inner_->drawIndexed(state, args);
    }
    bool drawIndirect(const rhi::DrawCallState& state, rhi::BufferHandle args, uint64_t offset, bool indexed) override {
        return inner_->drawIndirect(state, args, offset, indexed);
    }

    void beginMarker(const char* label) override { inner_->beginMarker(label); }
    void endMarker() override { inner_->endMarker(); }
    void setTimingEnabled(bool enabled) override { inner_->setTimingEnabled(enabled); }
    void setTimingDepth(uint32_t depth) override { inner_->setTimingDepth(depth); }
    std::vector<rhi::MarkerTiming> takeTimings() override { return inner_->takeTimings(); }

    void endFrame() override { inner_->endFrame(); }
    void waitIdle() override { inner_->waitIdle(); }

private:
    std::unique_ptr<rhi::IDevice> inner_;
};

}  // namespace example
