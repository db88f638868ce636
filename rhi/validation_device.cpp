// The validation wrapper: same interface as IDevice, checks each call, forwards only those that pass.
#include <cmath>
#include <cstdio>

#include "bricklight/rhi_validation.h"
#include "validation_internal.h"

namespace bricklight::rhi {

namespace {
using namespace validation;

std::string labelOf(const char* label) { return label && *label ? std::string(" '") + label + "'" : std::string(); }

class ValidationDevice final : public IDevice {
public:
    explicit ValidationDevice(IDevice& inner) : inner_(inner) {
        inner_.setErrorCallback([this](Severity s, const std::string& m) { emit(s, m); });
    }
    ~ValidationDevice() override { inner_.setErrorCallback(nullptr); }

    const Capabilities& capabilities() const override { return inner_.capabilities(); }
    void setErrorCallback(ErrorCallback cb) override { callback_ = std::move(cb); }

    TextureHandle createTexture(const TextureDesc& desc, const void* initialData) override {
        Report r{"createTexture" + labelOf(desc.debugName.c_str())};
        checkTextureDesc(desc, caps(), r);
        if (!finish(r)) return {};
        TextureHandle h = inner_.createTexture(desc, initialData);
        if (h) adopt(objects_.textures, h.id, desc, "createTexture" + labelOf(desc.debugName.c_str()), "texture");
        return h;
    }
    BufferHandle createBuffer(const BufferDesc& desc, const void* initialData) override {
        Report r{"createBuffer" + labelOf(desc.debugName.c_str())};
        checkBufferDesc(desc, r);
        if (!finish(r)) return {};
        BufferHandle h = inner_.createBuffer(desc, initialData);
        if (h) adopt(objects_.buffers, h.id, desc, "createBuffer" + labelOf(desc.debugName.c_str()), "buffer");
        return h;
    }
    SamplerHandle createSampler(const SamplerDesc& desc) override {
        Report r{"createSampler" + labelOf(desc.debugName.c_str())};
        checkSamplerDesc(desc, r);
        if (!finish(r)) return {};
        SamplerHandle h = inner_.createSampler(desc);
        if (h) adopt(objects_.samplers, h.id, desc, "createSampler" + labelOf(desc.debugName.c_str()), "sampler");
        return h;
    }
    ShaderHandle createShader(const ShaderDesc& desc) override {
        std::string name = !desc.debugName.empty() ? desc.debugName : desc.blob ? desc.blob->name : "";
        Report r{"createShader" + labelOf(name.c_str())};
        checkShaderDesc(desc, caps(), r);
        if (!finish(r)) return {};
        ShaderHandle h = inner_.createShader(desc);
        if (h) adopt(objects_.shaders, h.id, ShaderInfo{desc.blob, name}, "createShader" + labelOf(name.c_str()), "shader");
        return h;
    }
    TextureHandle wrapNativeTexture(const TextureDesc& desc, NativeObject native) override {
        Report r{"wrapNativeTexture" + labelOf(desc.debugName.c_str())};
        checkTextureDesc(desc, caps(), r);
        if (!native.object) r.error("native.object is null");
        if (!finish(r)) return {};
        TextureHandle h = inner_.wrapNativeTexture(desc, native);
        if (h) adopt(objects_.textures, h.id, desc, "wrapNativeTexture" + labelOf(desc.debugName.c_str()), "texture");
        return h;
    }
    BufferHandle wrapNativeBuffer(const BufferDesc& desc, NativeObject native) override {
        Report r{"wrapNativeBuffer" + labelOf(desc.debugName.c_str())};
        checkBufferDesc(desc, r);
        if (!native.object) r.error("native.object is null");
        if (!finish(r)) return {};
        BufferHandle h = inner_.wrapNativeBuffer(desc, native);
        if (h) adopt(objects_.buffers, h.id, desc, "wrapNativeBuffer" + labelOf(desc.debugName.c_str()), "buffer");
        return h;
    }

    void destroy(TextureHandle h) override {
        Report r{"destroy(texture)"};
        if (const TextureDesc* d = liveTexture(objects_, h, "texture", r)) {
            objects_.destroyedTextures[h.id] = d->debugName;
            objects_.textures.erase(h.id);
            inner_.destroy(h);
        }
        finish(r);
    }
    void destroy(BufferHandle h) override {
        Report r{"destroy(buffer)"};
        if (const BufferDesc* d = liveBuffer(objects_, h, "buffer", r)) {
            objects_.destroyedBuffers[h.id] = d->debugName;
            objects_.buffers.erase(h.id);
            inner_.destroy(h);
        }
        finish(r);
    }
    void destroy(SamplerHandle h) override {
        Report r{"destroy(sampler)"};
        if (const SamplerDesc* d = liveSampler(objects_, h, "sampler", r)) {
            objects_.destroyedSamplers[h.id] = d->debugName;
            objects_.samplers.erase(h.id);
            inner_.destroy(h);
        }
        finish(r);
    }
    void destroy(ShaderHandle h) override {
        Report r{"destroy(shader)"};
        if (const ShaderInfo* s = liveShader(objects_, h, "shader", r)) {
            objects_.destroyedShaders[h.id] = s->name;
            objects_.shaders.erase(h.id);
            inner_.destroy(h);
        }
        finish(r);
    }
    const TextureDesc* describe(TextureHandle h) const override {
        auto it = objects_.textures.find(h.id);
        return it == objects_.textures.end() ? nullptr : &it->second;
    }
    const BufferDesc* describe(BufferHandle h) const override {
        auto it = objects_.buffers.find(h.id);
        return it == objects_.buffers.end() ? nullptr : &it->second;
    }

    bool writeBuffer(BufferHandle b, uint64_t offset, const void* data, uint64_t size) override {
        Report r{"writeBuffer"};
        if (const BufferDesc* d = liveBuffer(objects_, b, "buffer", r)) {
            r.call += labelOf(d->debugName.c_str());
            checkBufferRange(*d, offset, size, "offset/size", r);
        }
        if (!data && size) r.error("data is null");
        return finish(r) && inner_.writeBuffer(b, offset, data, size);
    }
    bool writeTexture(TextureHandle t, TextureSubresource sub, const void* data) override {
        Report r{"writeTexture"};
        if (const TextureDesc* d = liveTexture(objects_, t, "texture", r)) {
            r.call += labelOf(d->debugName.c_str());
            checkSubresource(*d, sub, "subresource", r);
        }
        if (!data) r.error("data is null");
        return finish(r) && inner_.writeTexture(t, sub, data);
    }
    bool copyBuffer(BufferHandle dst, uint64_t dstOffset, BufferHandle src, uint64_t srcOffset, uint64_t size) override {
        Report r{"copyBuffer"};
        const BufferDesc* d = liveBuffer(objects_, dst, "dst", r);
        const BufferDesc* s = liveBuffer(objects_, src, "src", r);
        if (d) checkBufferRange(*d, dstOffset, size, "dst range", r);
        if (s) checkBufferRange(*s, srcOffset, size, "src range", r);
        if (d && s && r.errors.empty() && dst == src && dstOffset < srcOffset + size && srcOffset < dstOffset + size)
            r.error("src and dst ranges overlap in the same buffer");
        if (size % 4 || dstOffset % 4 || srcOffset % 4) r.error("offsets and size must be multiples of 4");
        return finish(r) && inner_.copyBuffer(dst, dstOffset, src, srcOffset, size);
    }
    bool copyTexture(TextureHandle dst, TextureSubresource dstSub, TextureHandle src, TextureSubresource srcSub) override {
        Report r{"copyTexture"};
        const TextureDesc* d = liveTexture(objects_, dst, "dst", r);
        const TextureDesc* s = liveTexture(objects_, src, "src", r);
        if (d && s && checkSubresource(*d, dstSub, "dstSub", r) && checkSubresource(*s, srcSub, "srcSub", r)) {
            if (d->format != s->format)
                r.error(std::string("formats differ (") + formatName(s->format) + " to " + formatName(d->format) + ")");
            if (mipExtent(d->width, dstSub.mip) != mipExtent(s->width, srcSub.mip) ||
                mipExtent(d->height, dstSub.mip) != mipExtent(s->height, srcSub.mip) ||
                textureDepth(*d, dstSub.mip) != textureDepth(*s, srcSub.mip) ||
                subresourceLayerCount(*d, dstSub) != subresourceLayerCount(*s, srcSub))
                r.error("subresource sizes differ");
            if (dst == src && dstSub.mip == srcSub.mip) r.error("src and dst are the same subresource");
        }
        return finish(r) && inner_.copyTexture(dst, dstSub, src, srcSub);
    }
    bool clearBuffer(BufferHandle b, BufferRange range, uint32_t value) override {
        Report r{"clearBuffer"};
        if (const BufferDesc* d = liveBuffer(objects_, b, "buffer", r)) {
            r.call += labelOf(d->debugName.c_str());
            uint64_t size = range.size ? range.size : (range.offset < d->size ? d->size - range.offset : 0);
            if (checkBufferRange(*d, range.offset, size, "range", r) && (range.offset % 4 || size % 4))
                r.error("range offset and size must be multiples of 4");
        }
        return finish(r) && inner_.clearBuffer(b, range, value);
    }
    bool clearTexture(TextureHandle t, uint32_t baseMip, uint32_t mipCount, ClearValue value) override {
        Report r{"clearTexture"};
        if (const TextureDesc* d = liveTexture(objects_, t, "texture", r)) {
            r.call += labelOf(d->debugName.c_str());
            if (baseMip >= d->mipLevels || (mipCount && mipCount > d->mipLevels - baseMip))
                r.error("mip range " + std::to_string(baseMip) + "+" + std::to_string(mipCount) + " out of range (" +
                        std::to_string(d->mipLevels) + " mips)");
        }
        return finish(r) && inner_.clearTexture(t, baseMip, mipCount, value);
    }
    bool readBuffer(BufferHandle b, uint64_t offset, uint64_t size, void* out) override {
        Report r{"readBuffer"};
        if (const BufferDesc* d = liveBuffer(objects_, b, "buffer", r)) checkBufferRange(*d, offset, size, "range", r);
        if (!out && size) r.error("out is null");
        return finish(r) && inner_.readBuffer(b, offset, size, out);
    }
    uint64_t requestReadback(BufferHandle b, uint64_t offset, uint64_t size) override {
        Report r{"requestReadback"};
        if (const BufferDesc* d = liveBuffer(objects_, b, "buffer", r)) checkBufferRange(*d, offset, size, "range", r);
        if (!size) r.error("size is 0");
        return finish(r) ? inner_.requestReadback(b, offset, size) : 0;
    }
    ReadbackStatus pollReadback(uint64_t ticket, void* out) override {
        if (!out) {
            emit(Severity::Error, "pollReadback: out is null");
            return ReadbackStatus::Failed;
        }
        return inner_.pollReadback(ticket, out);
    }
    bool readTexture(TextureHandle t, TextureSubresource sub, void* out) override {
        Report r{"readTexture"};
        if (const TextureDesc* d = liveTexture(objects_, t, "texture", r)) checkSubresource(*d, sub, "subresource", r);
        if (!out) r.error("out is null");
        return finish(r) && inner_.readTexture(t, sub, out);
    }

    bool dispatch(const DispatchState& s, uint32_t x, uint32_t y, uint32_t z) override {
        Report r{dispatchName("dispatch", s)};
        checkDispatch(objects_, caps(), s, r);
        const uint32_t groups[3] = {x, y, z};
        for (int i = 0; i < 3; ++i)
            if (groups[i] > caps().limits.maxComputeGroupCount[i])
                r.error("group count " + std::to_string(groups[i]) + " in dimension " + "xyz"[i] +
                        " exceeds maxComputeGroupCount " + std::to_string(caps().limits.maxComputeGroupCount[i]));
        return finish(r) && inner_.dispatch(s, x, y, z);
    }
    bool dispatchIndirect(const DispatchState& s, BufferHandle args, uint64_t offset) override {
        Report r{dispatchName("dispatchIndirect", s)};
        checkDispatch(objects_, caps(), s, r);
        checkArgs(args, offset, sizeof(DispatchIndirectArgs), r);
        return finish(r) && inner_.dispatchIndirect(s, args, offset);
    }
    bool draw(const DrawCallState& s, const DrawArgs& a) override {
        Report r{drawName("draw", s)};
        checkDraw(objects_, caps(), s, r);
        if (r.errors.empty()) checkDrawFetch(objects_, s, a, r);
        return finish(r) && inner_.draw(s, a);
    }
    bool drawIndexed(const DrawCallState& s, const DrawIndexedArgs& a) override {
        Report r{drawName("drawIndexed", s)};
        checkDraw(objects_, caps(), s, r);
        checkIndexBuffer(s, r);
        if (r.errors.empty()) checkDrawFetch(objects_, s, a, r);
        return finish(r) && inner_.drawIndexed(s, a);
    }
    bool drawIndirect(const DrawCallState& s, BufferHandle args, uint64_t offset, bool indexed) override {
        Report r{drawName("drawIndirect", s)};
        checkDraw(objects_, caps(), s, r);
        if (indexed) checkIndexBuffer(s, r);
        checkArgs(args, offset, indexed ? sizeof(DrawIndexedArgs) : sizeof(DrawArgs), r);
        return finish(r) && inner_.drawIndirect(s, args, offset, indexed);
    }

    // Markers nest at most kMaxMarkerDepth deep: a deeper one is refused, and so is the endMarker that closes
    // it (refused markers are always the innermost, so a count is all it takes).
    void beginMarker(const char* label) override {
        if (markerDepth_ + refusedMarkers_ >= kMaxMarkerDepth) {
            if (refusedMarkers_++ == 0)
                emit(Severity::Error, "beginMarker" + labelOf(label) + ": " + std::to_string(markerDepth_ + refusedMarkers_) +
                                          " markers open, more than kMaxMarkerDepth " + std::to_string(kMaxMarkerDepth) +
                                          " (an endMarker missing?); refused");
            return;
        }
        ++markerDepth_;
        inner_.beginMarker(label ? label : "");
    }
    void endMarker() override {
        if (refusedMarkers_) {
            --refusedMarkers_;
            return;
        }
        if (markerDepth_ == 0) {
            emit(Severity::Error, "endMarker: no marker is open");
            return;
        }
        --markerDepth_;
        inner_.endMarker();
    }
    void setTimingEnabled(bool enabled) override { inner_.setTimingEnabled(enabled); }
    void setTimingDepth(uint32_t depth) override { inner_.setTimingDepth(depth); }
    std::vector<MarkerTiming> takeTimings() override { return inner_.takeTimings(); }
    void endFrame() override {
        if (markerDepth_ + refusedMarkers_)
            emit(Severity::Warning, "endFrame: " + std::to_string(markerDepth_ + refusedMarkers_) + " marker(s) still open");
        inner_.endFrame();
    }
    void waitIdle() override { inner_.waitIdle(); }

private:
    const Capabilities& caps() const { return inner_.capabilities(); }

    std::string shaderName(ShaderHandle h) const {
        auto it = objects_.shaders.find(h.id);
        return it == objects_.shaders.end() ? std::string("?") : it->second.name;
    }
    std::string dispatchName(const char* call, const DispatchState& s) const {
        return call + labelOf(s.label) + " (shader '" + shaderName(s.shader) + "')";
    }
    std::string drawName(const char* call, const DrawCallState& s) const {
        return call + labelOf(s.label) + " (shaders '" + shaderName(s.vertexShader) + "'" +
               (s.fragmentShader ? ", '" + shaderName(s.fragmentShader) + "'" : std::string()) + ")";
    }

    void checkArgs(BufferHandle args, uint64_t offset, uint64_t size, Report& r) {
        const BufferDesc* d = liveBuffer(objects_, args, "args", r);
        if (!d) return;
        if (!(d->usage & BufferUsage::IndirectArgs)) r.error("args: buffer '" + d->debugName + "' lacks BufferUsage::IndirectArgs");
        if (offset % 4) r.error("args: offset " + std::to_string(offset) + " is not a multiple of 4");
        checkBufferRange(*d, offset, size, "args", r);
    }
    void checkIndexBuffer(const DrawCallState& s, Report& r) {
        const BufferDesc* d = liveBuffer(objects_, s.indexBuffer.buffer, "indexBuffer.buffer", r);
        if (!d) return;
        if (!(d->usage & BufferUsage::Index)) r.error("indexBuffer: buffer '" + d->debugName + "' lacks BufferUsage::Index");
        uint32_t align = s.indexBuffer.format == IndexFormat::U16 ? 2 : 4;
        if (s.indexBuffer.offset % align) r.error("indexBuffer.offset is not aligned to the index size");
        if (s.indexBuffer.offset >= d->size) r.error("indexBuffer.offset is beyond the end of the buffer");
    }

    // Records a new object. A device that hands out an id still live is broken (an engine's RHI under the
    // conformance kit, say): every later use of the id would reach the wrong object, so it is reported here,
    // naming both; the new description replaces the old.
    template <typename Map, typename Desc>
    void adopt(Map& map, uint32_t id, Desc desc, const std::string& call, const char* kind) {
        auto [it, inserted] = map.try_emplace(id, std::move(desc));
        if (inserted) return;
        emit(Severity::Error, call + ": the device returned " + kind + " handle #" + std::to_string(id) +
                                  ", which is already live (created earlier and not destroyed)");
        it->second = std::move(desc);
    }

    // Sends the report; returns true when the call may be forwarded.
    bool finish(const Report& r) {
        for (const auto& w : r.warnings) emit(Severity::Warning, w);
        for (const auto& e : r.errors) emit(Severity::Error, e);
        return r.errors.empty();
    }
    void emit(Severity s, const std::string& message) {
        if (callback_) callback_(s, message);
        else if (s != Severity::Info) fprintf(stderr, "bricklight %s: %s\n", s == Severity::Error ? "error" : "warning", message.c_str());
    }

    IDevice& inner_;
    ErrorCallback callback_;
    ObjectTable objects_;
    uint32_t markerDepth_ = 0;     // forwarded markers open
    uint64_t refusedMarkers_ = 0;  // refused markers open (beyond kMaxMarkerDepth)
};

}  // namespace

std::unique_ptr<IDevice> createValidationDevice(IDevice& inner) { return std::make_unique<ValidationDevice>(inner); }

}  // namespace bricklight::rhi
