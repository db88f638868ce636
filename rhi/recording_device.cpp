// The recording device: one JSON object per line for every call, then the call goes to the inner device.
// Created handles are written with the id the inner device returned, so later lines refer to them.
#include <ostream>

#include "bricklight/rhi_validation.h"
#include "record_json.h"
#include "size_math.h"

namespace bricklight::rhi {

namespace {
using record::json;

class RecordingDevice final : public IDevice {
public:
    RecordingDevice(IDevice& inner, std::ostream& out) : inner_(inner), out_(out) {}

    const Capabilities& capabilities() const override { return inner_.capabilities(); }
    void setErrorCallback(ErrorCallback cb) override { inner_.setErrorCallback(std::move(cb)); }

    TextureHandle createTexture(const TextureDesc& d, const void* data) override {
        TextureHandle h = inner_.createTexture(d, data);
        json j{{"call", "createTexture"}, {"result", h.id}, {"desc", record::encode(d)}};
        // The initial data of a description whose size cannot be computed (no device accepts one) is left
        // out: counting it looped over every mip of a hostile mipLevels and shifted by 32 or more.
        if (data)
            if (const auto bytes = sizes::textureBytes(d)) j["data"] = record::base64Encode(data, *bytes);
        return write(j), h;
    }
    BufferHandle createBuffer(const BufferDesc& d, const void* data) override {
        BufferHandle h = inner_.createBuffer(d, data);
        json j{{"call", "createBuffer"}, {"result", h.id}, {"desc", record::encode(d)}};
        if (data) j["data"] = record::base64Encode(data, d.size);
        return write(j), h;
    }
    SamplerHandle createSampler(const SamplerDesc& d) override {
        SamplerHandle h = inner_.createSampler(d);
        return write({{"call", "createSampler"}, {"result", h.id}, {"desc", record::encode(d)}}), h;
    }
    ShaderHandle createShader(const ShaderDesc& d) override {
        ShaderHandle h = inner_.createShader(d);
        write({{"call", "createShader"}, {"result", h.id}, {"blob", d.blob ? d.blob->name : ""}, {"debugName", d.debugName}});
        return h;
    }
    TextureHandle wrapNativeTexture(const TextureDesc& d, NativeObject n) override {
        TextureHandle h = inner_.wrapNativeTexture(d, n);
        // A native object cannot be replayed elsewhere; the replayer creates an ordinary texture instead.
        return write({{"call", "wrapNativeTexture"}, {"result", h.id}, {"desc", record::encode(d)}}), h;
    }
    BufferHandle wrapNativeBuffer(const BufferDesc& d, NativeObject n) override {
        BufferHandle h = inner_.wrapNativeBuffer(d, n);
        return write({{"call", "wrapNativeBuffer"}, {"result", h.id}, {"desc", record::encode(d)}}), h;
    }
    void destroy(TextureHandle h) override { write({{"call", "destroyTexture"}, {"handle", h.id}}), inner_.destroy(h); }
    void destroy(BufferHandle h) override { write({{"call", "destroyBuffer"}, {"handle", h.id}}), inner_.destroy(h); }
    void destroy(SamplerHandle h) override { write({{"call", "destroySampler"}, {"handle", h.id}}), inner_.destroy(h); }
    void destroy(ShaderHandle h) override { write({{"call", "destroyShader"}, {"handle", h.id}}), inner_.destroy(h); }
    const TextureDesc* describe(TextureHandle h) const override { return inner_.describe(h); }
    const BufferDesc* describe(BufferHandle h) const override { return inner_.describe(h); }

    bool writeBuffer(BufferHandle b, uint64_t offset, const void* data, uint64_t size) override {
        // The size too: a write with null data and a size is replayed as such (and fails again).
        write({{"call", "writeBuffer"}, {"buffer", b.id}, {"offset", offset}, {"size", size},
               {"data", record::base64Encode(data, data ? size : 0)}});
        return inner_.writeBuffer(b, offset, data, size);
    }
    bool writeTexture(TextureHandle t, TextureSubresource sub, const void* data) override {
        const TextureDesc* d = inner_.describe(t);
        const auto bytes = d && data ? sizes::subresourceBytes(*d, sub) : std::nullopt;  // none outside the texture
        write({{"call", "writeTexture"}, {"texture", t.id}, {"sub", {sub.mip, sub.layer, sub.layerCount}},
               {"data", record::base64Encode(data, bytes ? *bytes : 0)}});
        return inner_.writeTexture(t, sub, data);
    }
    bool copyBuffer(BufferHandle dst, uint64_t dstOffset, BufferHandle src, uint64_t srcOffset, uint64_t size) override {
        write({{"call", "copyBuffer"}, {"dst", dst.id}, {"dstOffset", dstOffset}, {"src", src.id}, {"srcOffset", srcOffset},
               {"size", size}});
        return inner_.copyBuffer(dst, dstOffset, src, srcOffset, size);
    }
    bool copyTexture(TextureHandle dst, TextureSubresource ds, TextureHandle src, TextureSubresource ss) override {
        write({{"call", "copyTexture"}, {"dst", dst.id}, {"dstSub", {ds.mip, ds.layer, ds.layerCount}}, {"src", src.id},
               {"srcSub", {ss.mip, ss.layer, ss.layerCount}}});
        return inner_.copyTexture(dst, ds, src, ss);
    }
    bool clearBuffer(BufferHandle b, BufferRange r, uint32_t value) override {
        write({{"call", "clearBuffer"}, {"buffer", b.id}, {"offset", r.offset}, {"size", r.size}, {"value", value}});
        return inner_.clearBuffer(b, r, value);
    }
    bool clearTexture(TextureHandle t, uint32_t baseMip, uint32_t mipCount, ClearValue v) override {
        write({{"call", "clearTexture"}, {"texture", t.id}, {"baseMip", baseMip}, {"mipCount", mipCount},
               {"value", {v.u[0], v.u[1], v.u[2], v.u[3]}}});
        return inner_.clearTexture(t, baseMip, mipCount, v);
    }
    bool readBuffer(BufferHandle b, uint64_t offset, uint64_t size, void* out) override {
        write({{"call", "readBuffer"}, {"buffer", b.id}, {"offset", offset}, {"size", size}});
        return inner_.readBuffer(b, offset, size, out);
    }
    uint64_t requestReadback(BufferHandle b, uint64_t offset, uint64_t size) override {
        write({{"call", "requestReadback"}, {"buffer", b.id}, {"offset", offset}, {"size", size}});
        return inner_.requestReadback(b, offset, size);
    }
    ReadbackStatus pollReadback(uint64_t ticket, void* out) override { return inner_.pollReadback(ticket, out); }
    bool readTexture(TextureHandle t, TextureSubresource sub, void* out) override {
        write({{"call", "readTexture"}, {"texture", t.id}, {"sub", {sub.mip, sub.layer, sub.layerCount}}});
        return inner_.readTexture(t, sub, out);
    }
    bool dispatch(const DispatchState& s, uint32_t x, uint32_t y, uint32_t z) override {
        write({{"call", "dispatch"}, {"state", record::encode(s)}, {"groups", {x, y, z}}});
        return inner_.dispatch(s, x, y, z);
    }
    bool dispatchIndirect(const DispatchState& s, BufferHandle args, uint64_t offset) override {
        write({{"call", "dispatchIndirect"}, {"state", record::encode(s)}, {"args", args.id}, {"offset", offset}});
        return inner_.dispatchIndirect(s, args, offset);
    }
    bool draw(const DrawCallState& s, const DrawArgs& a) override {
        write({{"call", "draw"}, {"state", record::encode(s)},
               {"args", {a.vertexCount, a.instanceCount, a.firstVertex, a.firstInstance}}});
        return inner_.draw(s, a);
    }
    bool drawIndexed(const DrawCallState& s, const DrawIndexedArgs& a) override {
        write({{"call", "drawIndexed"}, {"state", record::encode(s)},
               {"args", {a.indexCount, a.instanceCount, a.firstIndex, a.vertexOffset, a.firstInstance}}});
        return inner_.drawIndexed(s, a);
    }
    bool drawIndirect(const DrawCallState& s, BufferHandle args, uint64_t offset, bool indexed) override {
        write({{"call", "drawIndirect"}, {"state", record::encode(s)}, {"args", args.id}, {"offset", offset},
               {"indexed", indexed}});
        return inner_.drawIndirect(s, args, offset, indexed);
    }
    void beginMarker(const char* label) override {
        write({{"call", "beginMarker"}, {"label", label ? label : ""}});
        inner_.beginMarker(label);
    }
    void endMarker() override { write({{"call", "endMarker"}}), inner_.endMarker(); }
    void setTimingEnabled(bool e) override { write({{"call", "setTimingEnabled"}, {"enabled", e}}), inner_.setTimingEnabled(e); }
    void setTimingDepth(uint32_t depth) override { write({{"call", "setTimingDepth"}, {"depth", depth}}), inner_.setTimingDepth(depth); }
    std::vector<MarkerTiming> takeTimings() override { return inner_.takeTimings(); }
    void endFrame() override { write({{"call", "endFrame"}}), inner_.endFrame(); }
    void waitIdle() override { write({{"call", "waitIdle"}}), inner_.waitIdle(); }

private:
    // Names and labels come from the application and need not be UTF-8, which JSON must be: dump() would
    // throw out of the call; invalid bytes become U+FFFD instead.
    void write(const json& j) { out_ << j.dump(-1, ' ', false, json::error_handler_t::replace) << '\n'; }

    IDevice& inner_;
    std::ostream& out_;
};

}  // namespace

std::unique_ptr<IDevice> createRecordingDevice(IDevice& inner, std::ostream& out) {
    return std::make_unique<RecordingDevice>(inner, out);
}

}  // namespace bricklight::rhi
