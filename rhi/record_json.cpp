// Encoding and decoding of records as JSON. Field names follow the C++ field names so a recording reads
// like the code that made it.
#include "record_json.h"

#include <cstring>

namespace bricklight::rhi::record {

namespace {
const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

json encodeView(const TextureView& v) {
    return json{{"texture", v.texture.id}, {"format", formatName(v.format)}, {"baseMip", v.baseMip},
                {"mipCount", v.mipCount}, {"baseLayer", v.baseLayer}, {"layerCount", v.layerCount}};
}
json encodeRange(const BufferRange& r) { return json{{"offset", r.offset}, {"size", r.size}}; }

TextureView decodeView(const json& j, DecodeContext& ctx) {
    TextureView v;
    v.texture = ctx.map<TextureHandle>(ctx.textures, j.at("texture"));
    v.format = formatFromName(j.at("format").get<std::string>());
    v.baseMip = j.at("baseMip").get<uint8_t>();
    v.mipCount = j.at("mipCount").get<uint8_t>();
    v.baseLayer = j.at("baseLayer").get<uint16_t>();
    v.layerCount = j.at("layerCount").get<uint16_t>();
    return v;
}
BufferRange decodeRange(const json& j) { return BufferRange{j.at("offset").get<uint64_t>(), j.at("size").get<uint64_t>()}; }

template <typename T, size_t N, typename F>
void decodeArray(const json& j, const char* key, FixedVector<T, N>& out, F f) {
    if (!j.contains(key)) return;
    for (const auto& e : j.at(key)) out.push(f(e));
}

const char* labelOf(const json& j, DecodeContext& ctx) {
    if (!j.contains("label") || j.at("label").is_null()) return nullptr;
    ctx.labels.push_back(j.at("label").get<std::string>());
    return ctx.labels.back().c_str();
}

bool decodeBindings(const json& j, Bindings* b, DecodeContext& ctx) {
    decodeArray(j, "constants", b->constants, [&](const json& e) {
        ctx.constantStorage.emplace_back();
        base64Decode(e.at("data").get<std::string>(), &ctx.constantStorage.back());
        auto& bytes = ctx.constantStorage.back();
        return ConstantsBinding{e.at("slot").get<uint8_t>(), bytes.data(), static_cast<uint32_t>(bytes.size())};
    });
    decodeArray(j, "textures", b->textures, [&](const json& e) {
        return TextureBinding{e.at("slot").get<uint8_t>(), decodeView(e.at("view"), ctx),
                              ctx.map<SamplerHandle>(ctx.samplers, e.at("sampler"))};
    });
    decodeArray(j, "readBuffers", b->readBuffers, [&](const json& e) {
        return ReadBufferBinding{e.at("slot").get<uint8_t>(), ctx.map<BufferHandle>(ctx.buffers, e.at("buffer")),
                                 decodeRange(e.at("range"))};
    });
    decodeArray(j, "storageBuffers", b->storageBuffers, [&](const json& e) {
        return StorageBufferBinding{e.at("slot").get<uint8_t>(), ctx.map<BufferHandle>(ctx.buffers, e.at("buffer")),
                                    decodeRange(e.at("range")), static_cast<Access>(e.at("access").get<int>())};
    });
    decodeArray(j, "storageImages", b->storageImages, [&](const json& e) {
        return StorageImageBinding{e.at("slot").get<uint8_t>(), decodeView(e.at("view"), ctx),
                                   static_cast<Access>(e.at("access").get<int>())};
    });
    return ctx.error.empty();
}
}  // namespace

std::string base64Encode(const void* data, size_t size) {
    const uint8_t* p = static_cast<const uint8_t*>(data);
    std::string out;
    out.reserve((size + 2) / 3 * 4);
    for (size_t i = 0; i < size; i += 3) {
        uint32_t v = uint32_t(p[i]) << 16 | (i + 1 < size ? uint32_t(p[i + 1]) << 8 : 0) | (i + 2 < size ? p[i + 2] : 0);
        out += kAlphabet[v >> 18 & 63];
        out += kAlphabet[v >> 12 & 63];
        out += i + 1 < size ? kAlphabet[v >> 6 & 63] : '=';
        out += i + 2 < size ? kAlphabet[v & 63] : '=';
    }
    return out;
}

bool base64Decode(const std::string& text, std::vector<uint8_t>* out) {
    out->clear();
    uint32_t v = 0;
    int bits = 0;
    for (char c : text) {
        if (c == '=') break;
        const char* pos = std::strchr(kAlphabet, c);
        if (!pos || !c) return false;
        v = v << 6 | uint32_t(pos - kAlphabet);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out->push_back(uint8_t(v >> bits & 0xFF));
        }
    }
    return true;
}

json encode(const TextureDesc& d) {
    return json{{"dimension", int(d.dimension)}, {"format", formatName(d.format)}, {"width", d.width},
                {"height", d.height}, {"depthOrLayers", d.depthOrLayers}, {"mipLevels", d.mipLevels},
                {"usage", d.usage}, {"debugName", d.debugName}};
}
json encode(const BufferDesc& d) {
    return json{{"size", d.size}, {"structStride", d.structStride}, {"usage", d.usage}, {"debugName", d.debugName}};
}
json encode(const SamplerDesc& d) {
    return json{{"minFilter", int(d.minFilter)}, {"magFilter", int(d.magFilter)}, {"mipFilter", int(d.mipFilter)},
                {"addressU", int(d.addressU)}, {"addressV", int(d.addressV)}, {"addressW", int(d.addressW)},
                {"borderColor", int(d.borderColor)}, {"minLod", d.minLod}, {"maxLod", d.maxLod},
                {"mipLodBias", d.mipLodBias}, {"maxAnisotropy", d.maxAnisotropy},
                {"compareEnable", d.compareEnable}, {"compareOp", int(d.compareOp)}, {"debugName", d.debugName}};
}

json encode(const Bindings& b) {
    json j = json::object();
    for (const auto& c : b.constants)
        j["constants"].push_back({{"slot", c.slot}, {"data", base64Encode(c.data, c.data ? c.size : 0)}});
    for (const auto& t : b.textures)
        j["textures"].push_back({{"slot", t.slot}, {"view", encodeView(t.view)}, {"sampler", t.sampler.id}});
    for (const auto& r : b.readBuffers)
        j["readBuffers"].push_back({{"slot", r.slot}, {"buffer", r.buffer.id}, {"range", encodeRange(r.range)}});
    for (const auto& s : b.storageBuffers)
        j["storageBuffers"].push_back({{"slot", s.slot}, {"buffer", s.buffer.id}, {"range", encodeRange(s.range)},
                                       {"access", int(s.access)}, {"accessName", accessName(s.access)}});
    for (const auto& i : b.storageImages)
        j["storageImages"].push_back({{"slot", i.slot}, {"view", encodeView(i.view)}, {"access", int(i.access)},
                                      {"accessName", accessName(i.access)}});
    return j;
}

json encode(const DispatchState& s) {
    json j{{"shader", s.shader.id}, {"bindings", encode(s.bindings)}, {"flags", s.flags}};
    j["label"] = s.label ? json(s.label) : json(nullptr);
    return j;
}

json encode(const DrawCallState& s) {
    json j{{"vertexShader", s.vertexShader.id}, {"geometryShader", s.geometryShader.id},
           {"fragmentShader", s.fragmentShader.id}, {"topology", int(s.topology)}, {"bindings", encode(s.bindings)}};
    j["label"] = s.label ? json(s.label) : json(nullptr);
    j["vertexInputs"] = json::array();
    for (const auto& v : s.vertexInputs)
        j["vertexInputs"].push_back({{"location", v.location}, {"format", int(v.format)}, {"bufferIndex", v.bufferIndex},
                                     {"offset", v.offset}});
    j["vertexBuffers"] = json::array();
    for (const auto& v : s.vertexBuffers)
        j["vertexBuffers"].push_back({{"buffer", v.buffer.id}, {"offset", v.offset}, {"stride", v.stride},
                                      {"perInstance", v.perInstance}});
    j["indexBuffer"] = {{"buffer", s.indexBuffer.buffer.id}, {"offset", s.indexBuffer.offset},
                        {"format", int(s.indexBuffer.format)}};
    j["colorTargets"] = json::array();
    for (const auto& c : s.colorTargets) {
        const BlendState& b = c.blend;
        j["colorTargets"].push_back(
            {{"view", encodeView(c.view)}, {"load", int(c.load)},
             {"clearColor", {c.clearColor[0], c.clearColor[1], c.clearColor[2], c.clearColor[3]}},
             {"blend", {b.enable, int(b.srcColor), int(b.dstColor), int(b.colorOp), int(b.srcAlpha), int(b.dstAlpha),
                        int(b.alphaOp), b.writeMask}}});
    }
    j["depthTarget"] = {{"view", encodeView(s.depthTarget.view)}, {"load", int(s.depthTarget.load)},
                        {"clearDepth", s.depthTarget.clearDepth}};
    j["depth"] = {s.depth.testEnable, s.depth.writeEnable, int(s.depth.compare)};
    j["raster"] = {int(s.raster.cull), int(s.raster.frontFace), s.raster.depthClamp, s.raster.depthBiasConstant,
                   s.raster.depthBiasSlope};
    j["viewport"] = {s.viewport.x, s.viewport.y, s.viewport.width, s.viewport.height, s.viewport.minDepth,
                     s.viewport.maxDepth};
    j["scissor"] = {s.scissor.x, s.scissor.y, s.scissor.width, s.scissor.height};
    return j;
}

bool decode(const json& j, TextureDesc* d) {
    d->dimension = static_cast<TextureDimension>(j.at("dimension").get<int>());
    d->format = formatFromName(j.at("format").get<std::string>());
    d->width = j.at("width");
    d->height = j.at("height");
    d->depthOrLayers = j.at("depthOrLayers");
    d->mipLevels = j.at("mipLevels");
    d->usage = j.at("usage");
    d->debugName = j.at("debugName");
    return true;
}
bool decode(const json& j, BufferDesc* d) {
    d->size = j.at("size");
    d->structStride = j.at("structStride");
    d->usage = j.at("usage");
    d->debugName = j.at("debugName");
    return true;
}
bool decode(const json& j, SamplerDesc* d) {
    d->minFilter = static_cast<Filter>(j.at("minFilter").get<int>());
    d->magFilter = static_cast<Filter>(j.at("magFilter").get<int>());
    d->mipFilter = static_cast<Filter>(j.at("mipFilter").get<int>());
    d->addressU = static_cast<AddressMode>(j.at("addressU").get<int>());
    d->addressV = static_cast<AddressMode>(j.at("addressV").get<int>());
    d->addressW = static_cast<AddressMode>(j.at("addressW").get<int>());
    d->borderColor = static_cast<BorderColor>(j.at("borderColor").get<int>());
    d->minLod = j.at("minLod");
    d->maxLod = j.at("maxLod");
    d->mipLodBias = j.at("mipLodBias");
    d->maxAnisotropy = j.at("maxAnisotropy");
    d->compareEnable = j.at("compareEnable");
    d->compareOp = static_cast<CompareOp>(j.at("compareOp").get<int>());
    d->debugName = j.at("debugName");
    return true;
}

bool decode(const json& j, DispatchState* s, DecodeContext& ctx) {
    s->shader = ctx.map<ShaderHandle>(ctx.shaders, j.at("shader"));
    s->flags = j.at("flags");
    s->label = labelOf(j, ctx);
    return decodeBindings(j.at("bindings"), &s->bindings, ctx);
}

bool decode(const json& j, DrawCallState* s, DecodeContext& ctx) {
    s->vertexShader = ctx.map<ShaderHandle>(ctx.shaders, j.at("vertexShader"));
    s->geometryShader = ctx.map<ShaderHandle>(ctx.shaders, j.at("geometryShader"));
    s->fragmentShader = ctx.map<ShaderHandle>(ctx.shaders, j.at("fragmentShader"));
    s->topology = static_cast<PrimitiveTopology>(j.at("topology").get<int>());
    s->label = labelOf(j, ctx);
    for (const auto& v : j.at("vertexInputs"))
        s->vertexInputs.push(VertexInput{v.at("location"), static_cast<VertexFormat>(v.at("format").get<int>()),
                                         v.at("bufferIndex"), v.at("offset")});
    for (const auto& v : j.at("vertexBuffers"))
        s->vertexBuffers.push(VertexBufferBinding{ctx.map<BufferHandle>(ctx.buffers, v.at("buffer")), v.at("offset"),
                                                  v.at("stride"), v.at("perInstance")});
    const json& ib = j.at("indexBuffer");
    s->indexBuffer = IndexBufferBinding{ctx.map<BufferHandle>(ctx.buffers, ib.at("buffer")), ib.at("offset"),
                                        static_cast<IndexFormat>(ib.at("format").get<int>())};
    for (const auto& c : j.at("colorTargets")) {
        ColorTarget t;
        t.view = decodeView(c.at("view"), ctx);
        t.load = static_cast<LoadOp>(c.at("load").get<int>());
        for (int i = 0; i < 4; ++i) t.clearColor[i] = c.at("clearColor")[i];
        const json& b = c.at("blend");
        t.blend = BlendState{b[0], static_cast<BlendFactor>(b[1].get<int>()), static_cast<BlendFactor>(b[2].get<int>()),
                             static_cast<BlendOp>(b[3].get<int>()), static_cast<BlendFactor>(b[4].get<int>()),
                             static_cast<BlendFactor>(b[5].get<int>()), static_cast<BlendOp>(b[6].get<int>()), b[7]};
        s->colorTargets.push(t);
    }
    const json& dt = j.at("depthTarget");
    s->depthTarget.view = decodeView(dt.at("view"), ctx);
    s->depthTarget.load = static_cast<LoadOp>(dt.at("load").get<int>());
    s->depthTarget.clearDepth = dt.at("clearDepth");
    const json& d = j.at("depth");
    s->depth = DepthState{d[0], d[1], static_cast<CompareOp>(d[2].get<int>())};
    const json& r = j.at("raster");
    s->raster = RasterState{static_cast<CullMode>(r[0].get<int>()), static_cast<FrontFace>(r[1].get<int>()), r[2], r[3], r[4]};
    const json& v = j.at("viewport");
    s->viewport = Viewport{v[0], v[1], v[2], v[3], v[4], v[5]};
    const json& sc = j.at("scissor");
    s->scissor = ScissorRect{sc[0], sc[1], sc[2], sc[3]};
    return decodeBindings(j.at("bindings"), &s->bindings, ctx);
}

}  // namespace bricklight::rhi::record
