// A device that hands every call to another one: the base of the test devices that change one behaviour
// (keep buffer contents, throw from a call) and leave the rest to the null device.
#pragma once

#include <utility>
#include <vector>

#include "bricklight/rhi.h"

namespace bricklight::testing {

class ForwardingTestDevice : public rhi::IDevice {
public:
    explicit ForwardingTestDevice(rhi::IDevice& inner) : inner_(inner) {}

    const rhi::Capabilities& capabilities() const override { return inner_.capabilities(); }
    void setErrorCallback(rhi::ErrorCallback cb) override { inner_.setErrorCallback(std::move(cb)); }
    rhi::TextureHandle createTexture(const rhi::TextureDesc& d, const void* data) override { return inner_.createTexture(d, data); }
    rhi::BufferHandle createBuffer(const rhi::BufferDesc& d, const void* data) override { return inner_.createBuffer(d, data); }
    rhi::SamplerHandle createSampler(const rhi::SamplerDesc& d) override { return inner_.createSampler(d); }
    rhi::ShaderHandle createShader(const rhi::ShaderDesc& d) override { return inner_.createShader(d); }
    rhi::TextureHandle wrapNativeTexture(const rhi::TextureDesc& d, rhi::NativeObject n) override { return inner_.wrapNativeTexture(d, n); }
    rhi::BufferHandle wrapNativeBuffer(const rhi::BufferDesc& d, rhi::NativeObject n) override { return inner_.wrapNativeBuffer(d, n); }
    void destroy(rhi::TextureHandle h) override { inner_.destroy(h); }
    void destroy(rhi::BufferHandle h) override { inner_.destroy(h); }
    void destroy(rhi::SamplerHandle h) override { inner_.destroy(h); }
    void destroy(rhi::ShaderHandle h) override { inner_.destroy(h); }
    const rhi::TextureDesc* describe(rhi::TextureHandle h) const override { return inner_.describe(h); }
    const rhi::BufferDesc* describe(rhi::BufferHandle h) const override { return inner_.describe(h); }
    bool writeBuffer(rhi::BufferHandle b, uint64_t o, const void* d, uint64_t s) override { return inner_.writeBuffer(b, o, d, s); }
    bool writeTexture(rhi::TextureHandle t, rhi::TextureSubresource s, const void* d) override { return inner_.writeTexture(t, s, d); }
    bool copyBuffer(rhi::BufferHandle d, uint64_t dO, rhi::BufferHandle s, uint64_t sO, uint64_t n) override {
        return inner_.copyBuffer(d, dO, s, sO, n);
    }
    bool copyTexture(rhi::TextureHandle d, rhi::TextureSubresource dS, rhi::TextureHandle s, rhi::TextureSubresource sS) override {
        return inner_.copyTexture(d, dS, s, sS);
    }
    bool clearBuffer(rhi::BufferHandle b, rhi::BufferRange r, uint32_t v) override { return inner_.clearBuffer(b, r, v); }
    bool clearTexture(rhi::TextureHandle t, uint32_t m, uint32_t n, rhi::ClearValue v) override { return inner_.clearTexture(t, m, n, v); }
    bool readBuffer(rhi::BufferHandle b, uint64_t o, uint64_t s, void* out) override { return inner_.readBuffer(b, o, s, out); }
    bool readTexture(rhi::TextureHandle t, rhi::TextureSubresource s, void* out) override { return inner_.readTexture(t, s, out); }
    uint64_t requestReadback(rhi::BufferHandle b, uint64_t o, uint64_t s) override { return inner_.requestReadback(b, o, s); }
    rhi::ReadbackStatus pollReadback(uint64_t t, void* out) override { return inner_.pollReadback(t, out); }
    bool dispatch(const rhi::DispatchState& s, uint32_t x, uint32_t y, uint32_t z) override { return inner_.dispatch(s, x, y, z); }
    bool dispatchIndirect(const rhi::DispatchState& s, rhi::BufferHandle a, uint64_t o) override { return inner_.dispatchIndirect(s, a, o); }
    bool draw(const rhi::DrawCallState& s, const rhi::DrawArgs& a) override { return inner_.draw(s, a); }
    bool drawIndexed(const rhi::DrawCallState& s, const rhi::DrawIndexedArgs& a) override { return inner_.drawIndexed(s, a); }
    bool drawIndirect(const rhi::DrawCallState& s, rhi::BufferHandle a, uint64_t o, bool i) override {
        return inner_.drawIndirect(s, a, o, i);
    }
    void beginMarker(const char* l) override { inner_.beginMarker(l); }
    void endMarker() override { inner_.endMarker(); }
    void setTimingEnabled(bool e) override { inner_.setTimingEnabled(e); }
    void setTimingDepth(uint32_t d) override { inner_.setTimingDepth(d); }
    std::vector<rhi::MarkerTiming> takeTimings() override { return inner_.takeTimings(); }
    void endFrame() override { inner_.endFrame(); }
    void waitIdle() override { inner_.waitIdle(); }

protected:
    rhi::IDevice& inner_;
};

}  // namespace bricklight::testing
