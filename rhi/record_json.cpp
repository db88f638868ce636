// Encoding and decoding of records as JSON. Field names follow the C++ field names so a recording reads
// like the code that made it. Encoders and decoders sit side by side, one pair per record, so that a field
// added to one is seen missing from the other.
#include "record_json.h"

#include <cfloat>
#include <cmath>

namespace bricklight::rhi::record {

namespace {
const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int base64Value(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
}

std::string describeJson(const json& v) {
    switch (v.type()) {
        case json::value_t::null: return "null";
        case json::value_t::boolean: return "a boolean";
        case json::value_t::string: return "a string";
        case json::value_t::array: return "an array";
        case json::value_t::object: return "an object";
        case json::value_t::binary: return "binary data";
        case json::value_t::discarded: return "nothing";
        default: return "the number " + v.dump();
    }
}

std::string at(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }

// Lists (bindings, targets, inputs) fill a FixedVector; more entries than it holds is an error, not a
// silent drop.
template <typename T, size_t N, typename F>
void decodeList(const Fields& f, const char* key, bool required, FixedVector<T, N>& out, F decodeOne) {
    if (!required && !f.has(key)) return;
    const json& list = f.at(key);
    const std::string path = f.path(key);
    if (!list.is_array()) throw DecodeError(path + ": expected an array, got " + describeJson(list));
    if (list.size() > N)
        throw DecodeError(path + ": " + std::to_string(list.size()) + " entries exceed the capacity of " + std::to_string(N));
    for (size_t i = 0; i < list.size(); ++i) out.push(decodeOne(Fields(list[i], at(path, i))));
}

json encodeView(const TextureView& v) {
    return json{{"texture", v.texture.id}, {"format", formatName(v.format)}, {"baseMip", v.baseMip},
                {"mipCount", v.mipCount}, {"baseLayer", v.baseLayer}, {"layerCount", v.layerCount}};
}
Format decodeFormat(const Fields& f, const char* key) {
    const std::string& name = f.string(key);
    if (name == "Unknown") return Format::Unknown;
    const Format format = formatFromName(name);
    if (format == Format::Unknown) throw DecodeError(f.path(key) + ": '" + name.substr(0, 64) + "' is not a format name");
    return format;
}
TextureView decodeView(const Fields& f, DecodeContext& ctx) {
    TextureView v;
    v.texture = ctx.map<TextureHandle>(ctx.textures, f.at("texture"), f.path("texture"));
    v.format = decodeFormat(f, "format");
    v.baseMip = f.u8("baseMip");
    v.mipCount = f.u8("mipCount");
    v.baseLayer = f.u16("baseLayer");
    v.layerCount = f.u16("layerCount");
    return v;
}

json encodeRange(const BufferRange& r) { return json{{"offset", r.offset}, {"size", r.size}}; }
BufferRange decodeRange(const Fields& f) { return BufferRange{f.u64("offset"), f.u64("size")}; }

Bindings decodeBindings(const Fields& f, DecodeContext& ctx) {
    Bindings b;
    decodeList(f, "constants", false, b.constants, [&](const Fields& e) {
        const std::vector<uint8_t>& bytes = ctx.bytes(e.at("data"), e.path("data"));
        return ConstantsBinding{e.u8("slot"), bytes.empty() ? nullptr : bytes.data(), uint32_t(bytes.size())};
    });
    decodeList(f, "textures", false, b.textures, [&](const Fields& e) {
        return TextureBinding{e.u8("slot"), decodeView(e.object("view"), ctx),
                              ctx.map<SamplerHandle>(ctx.samplers, e.at("sampler"), e.path("sampler"))};
    });
    decodeList(f, "readBuffers", false, b.readBuffers, [&](const Fields& e) {
        return ReadBufferBinding{e.u8("slot"), ctx.map<BufferHandle>(ctx.buffers, e.at("buffer"), e.path("buffer")),
                                 decodeRange(e.object("range"))};
    });
    decodeList(f, "storageBuffers", false, b.storageBuffers, [&](const Fields& e) {
        return StorageBufferBinding{e.u8("slot"), ctx.map<BufferHandle>(ctx.buffers, e.at("buffer"), e.path("buffer")),
                                    decodeRange(e.object("range")), e.enumeration<Access>("access", 4)};
    });
    decodeList(f, "storageImages", false, b.storageImages, [&](const Fields& e) {
        return StorageImageBinding{e.u8("slot"), decodeView(e.object("view"), ctx), e.enumeration<Access>("access", 4)};
    });
    return b;
}

json encodeLabel(const char* label) { return label ? json(label) : json(nullptr); }
}  // namespace

// ---------------------------------------------------------------------------------------------------
// Base64 and floats
// ---------------------------------------------------------------------------------------------------
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

std::optional<size_t> base64DecodedSize(std::string_view text) {
    if (text.size() % 4) return std::nullopt;
    size_t padding = 0;
    if (!text.empty() && text.back() == '=') padding = text.size() >= 2 && text[text.size() - 2] == '=' ? 2 : 1;
    for (size_t i = 0; i + padding < text.size(); ++i)
        if (base64Value(text[i]) < 0) return std::nullopt;
    return text.size() / 4 * 3 - padding;
}

bool base64Decode(std::string_view text, std::vector<uint8_t>* out) {
    out->clear();
    const auto size = base64DecodedSize(text);
    if (!size) return false;
    out->reserve(*size);
    uint32_t v = 0;
    int bits = 0;
    for (char c : text) {
        if (c == '=') break;  // only trailing padding gets here (base64DecodedSize checked the rest)
        v = v << 6 | uint32_t(base64Value(c));
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out->push_back(uint8_t(v >> bits & 0xFF));
        }
    }
    return out->size() == *size;
}

json encodeFloat(float f) {
    if (std::isnan(f)) return "nan";
    if (std::isinf(f)) return f > 0 ? "inf" : "-inf";
    return f;
}

// ---------------------------------------------------------------------------------------------------
// Checked reads
// ---------------------------------------------------------------------------------------------------
uint64_t readUnsigned(const json& v, uint64_t max, const std::string& path, const char* typeName) {
    if (v.is_number_unsigned()) {
        const uint64_t u = v.get<uint64_t>();
        if (u <= max) return u;
        throw DecodeError(path + ": " + std::to_string(u) + " does not fit " + typeName + " (0.." + std::to_string(max) + ")");
    }
    if (v.is_number_integer())  // negative: nlohmann keeps non-negative integers as unsigned
        throw DecodeError(path + ": " + std::to_string(v.get<int64_t>()) + " does not fit " + typeName + " (0.." +
                          std::to_string(max) + ")");
    throw DecodeError(path + ": expected a whole number (" + typeName + "), got " + describeJson(v));
}

int64_t readSigned(const json& v, int64_t min, int64_t max, const std::string& path, const char* typeName) {
    const std::string range = " (" + std::to_string(min) + ".." + std::to_string(max) + ")";
    if (v.is_number_unsigned()) {
        const uint64_t u = v.get<uint64_t>();
        if (u <= uint64_t(max)) return int64_t(u);
        throw DecodeError(path + ": " + std::to_string(u) + " does not fit " + typeName + range);
    }
    if (v.is_number_integer()) {
        const int64_t i = v.get<int64_t>();
        if (i >= min && i <= max) return i;
        throw DecodeError(path + ": " + std::to_string(i) + " does not fit " + typeName + range);
    }
    throw DecodeError(path + ": expected a whole number (" + typeName + "), got " + describeJson(v));
}

float readFloat(const json& v, const std::string& path) {
    if (v.is_string()) {
        const std::string& s = v.get_ref<const std::string&>();
        if (s == "inf") return INFINITY;
        if (s == "-inf") return -INFINITY;
        if (s == "nan") return NAN;
        throw DecodeError(path + ": expected a number (or \"inf\", \"-inf\", \"nan\"), got a string");
    }
    if (!v.is_number()) throw DecodeError(path + ": expected a number, got " + describeJson(v));
    const double d = v.get<double>();
    // A double beyond the float range has no float value: converting it would be undefined behaviour.
    if (!(std::fabs(d) <= double(FLT_MAX))) throw DecodeError(path + ": " + v.dump() + " does not fit a float");
    return float(d);
}

bool readBool(const json& v, const std::string& path) {
    if (!v.is_boolean()) throw DecodeError(path + ": expected true or false, got " + describeJson(v));
    return v.get<bool>();
}

const std::string& readString(const json& v, const std::string& path) {
    if (!v.is_string()) throw DecodeError(path + ": expected a string, got " + describeJson(v));
    return v.get_ref<const std::string&>();
}

const json& readTuple(const json& v, size_t length, const std::string& path) {
    if (!v.is_array()) throw DecodeError(path + ": expected an array of " + std::to_string(length) + ", got " + describeJson(v));
    if (v.size() != length)
        throw DecodeError(path + ": expected " + std::to_string(length) + " elements, got " + std::to_string(v.size()));
    return v;
}

Fields::Fields(const json& object, std::string path) : object_(object), path_(std::move(path)) {
    if (!object_.is_object()) throw DecodeError((path_.empty() ? "line" : path_) + ": expected an object, got " + describeJson(object_));
}

const json& Fields::at(const char* key) const {
    auto it = object_.find(key);
    if (it == object_.end()) throw DecodeError(path(key) + ": missing");
    return *it;
}

const std::vector<uint8_t>& DecodeContext::bytes(const json& text, const std::string& path) {
    const std::string& s = readString(text, path);
    const auto size = base64DecodedSize(s);
    if (!size) throw DecodeError(path + ": not canonical base64 (" + std::to_string(s.size()) + " characters)");
    if (*size > dataBudget)
        throw DecodeError(path + ": " + std::to_string(*size) + " bytes of data exceed the limit of " +
                          std::to_string(maxDataBytes) + " bytes per line (ReplayOptions::maxDataBytes)");
    dataBudget -= *size;
    byteStorage.emplace_back();
    base64Decode(s, &byteStorage.back());
    return byteStorage.back();
}

const char* DecodeContext::label(const json& v, const std::string& path) {
    if (v.is_null()) return nullptr;
    labels.push_back(readString(v, path));
    return labels.back().c_str();
}

// ---------------------------------------------------------------------------------------------------
// Descriptions
// ---------------------------------------------------------------------------------------------------
json encode(const TextureDesc& d) {
    return json{{"dimension", int(d.dimension)}, {"format", formatName(d.format)}, {"width", d.width},
                {"height", d.height}, {"depthOrLayers", d.depthOrLayers}, {"mipLevels", d.mipLevels},
                {"usage", d.usage}, {"debugName", d.debugName}};
}
TextureDesc decodeTextureDesc(const Fields& f) {
    TextureDesc d;
    d.dimension = f.enumeration<TextureDimension>("dimension", 4);
    d.format = decodeFormat(f, "format");
    d.width = f.u32("width");
    d.height = f.u32("height");
    d.depthOrLayers = f.u32("depthOrLayers");
    d.mipLevels = f.u32("mipLevels");
    d.usage = f.u32("usage");
    d.debugName = f.string("debugName");
    return d;
}

json encode(const BufferDesc& d) {
    return json{{"size", d.size}, {"structStride", d.structStride}, {"usage", d.usage}, {"debugName", d.debugName}};
}
BufferDesc decodeBufferDesc(const Fields& f) {
    BufferDesc d;
    d.size = f.u64("size");
    d.structStride = f.u32("structStride");
    d.usage = f.u32("usage");
    d.debugName = f.string("debugName");
    return d;
}

json encode(const SamplerDesc& d) {
    return json{{"minFilter", int(d.minFilter)}, {"magFilter", int(d.magFilter)}, {"mipFilter", int(d.mipFilter)},
                {"addressU", int(d.addressU)}, {"addressV", int(d.addressV)}, {"addressW", int(d.addressW)},
                {"borderColor", int(d.borderColor)}, {"minLod", encodeFloat(d.minLod)},
                {"maxLod", encodeFloat(d.maxLod)}, {"mipLodBias", encodeFloat(d.mipLodBias)},
                {"maxAnisotropy", encodeFloat(d.maxAnisotropy)}, {"compareEnable", d.compareEnable},
                {"compareOp", int(d.compareOp)}, {"debugName", d.debugName}};
}
SamplerDesc decodeSamplerDesc(const Fields& f) {
    SamplerDesc d;
    d.minFilter = f.enumeration<Filter>("minFilter", 2);
    d.magFilter = f.enumeration<Filter>("magFilter", 2);
    d.mipFilter = f.enumeration<Filter>("mipFilter", 2);
    d.addressU = f.enumeration<AddressMode>("addressU", 4);
    d.addressV = f.enumeration<AddressMode>("addressV", 4);
    d.addressW = f.enumeration<AddressMode>("addressW", 4);
    d.borderColor = f.enumeration<BorderColor>("borderColor", 3);
    d.minLod = f.f32("minLod");
    d.maxLod = f.f32("maxLod");
    d.mipLodBias = f.f32("mipLodBias");
    d.maxAnisotropy = f.f32("maxAnisotropy");
    d.compareEnable = f.boolean("compareEnable");
    d.compareOp = f.enumeration<CompareOp>("compareOp", 8);
    d.debugName = f.string("debugName");
    return d;
}

// ---------------------------------------------------------------------------------------------------
// Records
// ---------------------------------------------------------------------------------------------------
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
    return json{{"shader", s.shader.id}, {"bindings", encode(s.bindings)}, {"flags", s.flags}, {"label", encodeLabel(s.label)}};
}
DispatchState decodeDispatch(const Fields& f, DecodeContext& ctx) {
    DispatchState s;
    s.shader = ctx.map<ShaderHandle>(ctx.shaders, f.at("shader"), f.path("shader"));
    s.flags = f.u32("flags");
    s.label = f.has("label") ? ctx.label(f.at("label"), f.path("label")) : nullptr;
    s.bindings = decodeBindings(f.object("bindings"), ctx);
    return s;
}

json encode(const DrawCallState& s) {
    json j{{"vertexShader", s.vertexShader.id}, {"geometryShader", s.geometryShader.id},
           {"fragmentShader", s.fragmentShader.id}, {"topology", int(s.topology)}, {"bindings", encode(s.bindings)},
           {"label", encodeLabel(s.label)}};
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
             {"clearColor", {encodeFloat(c.clearColor[0]), encodeFloat(c.clearColor[1]), encodeFloat(c.clearColor[2]),
                             encodeFloat(c.clearColor[3])}},
             {"blend", {b.enable, int(b.srcColor), int(b.dstColor), int(b.colorOp), int(b.srcAlpha), int(b.dstAlpha),
                        int(b.alphaOp), b.writeMask}}});
    }
    j["depthTarget"] = {{"view", encodeView(s.depthTarget.view)}, {"load", int(s.depthTarget.load)},
                        {"clearDepth", encodeFloat(s.depthTarget.clearDepth)}};
    j["depth"] = {s.depth.testEnable, s.depth.writeEnable, int(s.depth.compare)};
    j["raster"] = {int(s.raster.cull), int(s.raster.frontFace), s.raster.depthClamp,
                   encodeFloat(s.raster.depthBiasConstant), encodeFloat(s.raster.depthBiasSlope)};
    j["viewport"] = {encodeFloat(s.viewport.x), encodeFloat(s.viewport.y), encodeFloat(s.viewport.width),
                     encodeFloat(s.viewport.height), encodeFloat(s.viewport.minDepth), encodeFloat(s.viewport.maxDepth)};
    j["scissor"] = {s.scissor.x, s.scissor.y, s.scissor.width, s.scissor.height};
    return j;
}

DrawCallState decodeDraw(const Fields& f, DecodeContext& ctx) {
    DrawCallState s;
    s.vertexShader = ctx.map<ShaderHandle>(ctx.shaders, f.at("vertexShader"), f.path("vertexShader"));
    s.geometryShader = ctx.map<ShaderHandle>(ctx.shaders, f.at("geometryShader"), f.path("geometryShader"));
    s.fragmentShader = ctx.map<ShaderHandle>(ctx.shaders, f.at("fragmentShader"), f.path("fragmentShader"));
    s.topology = f.enumeration<PrimitiveTopology>("topology", 4);
    s.label = f.has("label") ? ctx.label(f.at("label"), f.path("label")) : nullptr;
    decodeList(f, "vertexInputs", true, s.vertexInputs, [](const Fields& v) {
        return VertexInput{v.u8("location"), v.enumeration<VertexFormat>("format", 7), v.u8("bufferIndex"), v.u32("offset")};
    });
    decodeList(f, "vertexBuffers", true, s.vertexBuffers, [&](const Fields& v) {
        return VertexBufferBinding{ctx.map<BufferHandle>(ctx.buffers, v.at("buffer"), v.path("buffer")), v.u64("offset"),
                                   v.u32("stride"), v.boolean("perInstance")};
    });
    const Fields ib = f.object("indexBuffer");
    s.indexBuffer = IndexBufferBinding{ctx.map<BufferHandle>(ctx.buffers, ib.at("buffer"), ib.path("buffer")),
                                       ib.u64("offset"), ib.enumeration<IndexFormat>("format", 2)};
    decodeList(f, "colorTargets", true, s.colorTargets, [&](const Fields& c) {
        ColorTarget t;
        t.view = decodeView(c.object("view"), ctx);
        t.load = c.enumeration<LoadOp>("load", 3);
        const json& clear = c.tuple("clearColor", 4);
        for (size_t i = 0; i < 4; ++i) t.clearColor[i] = readFloat(clear[i], at(c.path("clearColor"), i));
        const json& b = c.tuple("blend", 8);
        const std::string bp = c.path("blend");
        auto factor = [&](size_t i) { return BlendFactor(readUnsigned(b[i], 9, at(bp, i), "BlendFactor")); };
        auto op = [&](size_t i) { return BlendOp(readUnsigned(b[i], 4, at(bp, i), "BlendOp")); };
        t.blend = BlendState{readBool(b[0], at(bp, 0)), factor(1), factor(2), op(3), factor(4), factor(5), op(6),
                             uint8_t(readUnsigned(b[7], UINT8_MAX, at(bp, 7), "uint8"))};
        return t;
    });
    const Fields dt = f.object("depthTarget");
    s.depthTarget.view = decodeView(dt.object("view"), ctx);
    s.depthTarget.load = dt.enumeration<LoadOp>("load", 3);
    s.depthTarget.clearDepth = dt.f32("clearDepth");
    const json& d = f.tuple("depth", 3);
    const std::string dp = f.path("depth");
    s.depth = DepthState{readBool(d[0], at(dp, 0)), readBool(d[1], at(dp, 1)),
                         CompareOp(readUnsigned(d[2], 7, at(dp, 2), "CompareOp"))};
    const json& r = f.tuple("raster", 5);
    const std::string rp = f.path("raster");
    s.raster = RasterState{CullMode(readUnsigned(r[0], 2, at(rp, 0), "CullMode")),
                           FrontFace(readUnsigned(r[1], 1, at(rp, 1), "FrontFace")), readBool(r[2], at(rp, 2)),
                           readFloat(r[3], at(rp, 3)), readFloat(r[4], at(rp, 4))};
    const json& v = f.tuple("viewport", 6);
    const std::string vp = f.path("viewport");
    s.viewport = Viewport{readFloat(v[0], at(vp, 0)), readFloat(v[1], at(vp, 1)), readFloat(v[2], at(vp, 2)),
                          readFloat(v[3], at(vp, 3)), readFloat(v[4], at(vp, 4)), readFloat(v[5], at(vp, 5))};
    const json& sc = f.tuple("scissor", 4);
    const std::string sp = f.path("scissor");
    s.scissor = ScissorRect{int32_t(readSigned(sc[0], INT32_MIN, INT32_MAX, at(sp, 0), "int32")),
                            int32_t(readSigned(sc[1], INT32_MIN, INT32_MAX, at(sp, 1), "int32")),
                            uint32_t(readUnsigned(sc[2], UINT32_MAX, at(sp, 2), "uint32")),
                            uint32_t(readUnsigned(sc[3], UINT32_MAX, at(sp, 3), "uint32"))};
    s.bindings = decodeBindings(f.object("bindings"), ctx);
    return s;
}

}  // namespace bricklight::rhi::record
