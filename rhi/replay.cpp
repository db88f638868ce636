// Replays a recording (JSON lines from the recording device) on any IDevice. A recording is untrusted
// input: each line is bounded (length, JSON values, decoded bytes, read-back size) before anything is
// allocated for it, decoded completely with every field checked (record_json.h) before the device is
// called, and any exception — a decode error, std::bad_alloc, whatever the device throws — ends the replay
// with an error naming the line instead of leaving the API.
#include <istream>
#include <unordered_map>

#include "bricklight/rhi_validation.h"
#include "bricklight/shader_blob.h"
#include "record_json.h"
#include "size_math.h"

namespace bricklight::rhi {

namespace {
using record::DecodeContext;
using record::DecodeError;
using record::Fields;
using record::json;

enum class LineStatus { Line, End, TooLong };

// A line past one of ReplayOptions' work or memory budgets (ReplayStats::overBudget).
struct OverBudget : DecodeError {
    using DecodeError::DecodeError;
};

uint64_t saturatingProduct(std::initializer_list<uint64_t> factors) {
    uint64_t p = 1;
    for (uint64_t f : factors)
        if (__builtin_mul_overflow(p, f, &p)) return UINT64_MAX;
    return p;
}

// One line, without its '\n', stopping (TooLong) as soon as it exceeds `maxBytes`: std::getline would first
// read a line of any length into memory.
LineStatus readLine(std::istream& in, std::string* line, uint64_t maxBytes) {
    line->clear();
    std::streambuf* buffer = in.rdbuf();
    if (!buffer) return LineStatus::End;
    bool any = false;
    for (;;) {
        const int c = buffer->sbumpc();
        if (c == std::char_traits<char>::eof()) return any ? LineStatus::Line : LineStatus::End;
        any = true;
        if (c == '\n') return LineStatus::Line;
        if (line->size() >= maxBytes) return LineStatus::TooLong;
        line->push_back(char(c));
    }
}

bool blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

// Counts the JSON values on a line (each scalar, array and object) without parsing it: a short line of
// "[[[[..." or "[0,0,0,..." would otherwise cost many times its length in parsed nodes.
uint64_t countJsonValues(const std::string& line) {
    uint64_t values = 1;
    bool inString = false, escaped = false;
    for (char c : line) {
        if (inString) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{' || c == ',' || c == ':') {
            ++values;
        }
    }
    return values;
}

TextureSubresource decodeSub(const Fields& f, const char* key) {
    const json& s = f.tuple(key, 3);
    const std::string p = f.path(key);
    return TextureSubresource{uint32_t(record::readUnsigned(s[0], UINT32_MAX, p + "[0]", "uint32")),
                              uint32_t(record::readUnsigned(s[1], UINT32_MAX, p + "[1]", "uint32")),
                              uint32_t(record::readUnsigned(s[2], UINT32_MAX, p + "[2]", "uint32"))};
}

class Replayer {
public:
    Replayer(IDevice& device, const ReplayOptions& options) : device_(device), options_(options) {}

    // Executes one recorded call; throws DecodeError when the line cannot be understood (nothing has been
    // called then). Returns whether the device accepted the call.
    bool replay(const json& line, uint64_t lineNumber) {
        lineNumber_ = lineNumber;
        const Fields f(line, "");
        const std::string& call = f.string("call");
        ctx_.startLine(options_.maxDataBytes);
        using Handler = bool (Replayer::*)(const Fields&);
        static const std::unordered_map<std::string, Handler> handlers = {
            {"createTexture", &Replayer::createTexture}, {"wrapNativeTexture", &Replayer::createTexture},
            {"createBuffer", &Replayer::createBuffer}, {"wrapNativeBuffer", &Replayer::createBuffer},
            {"createSampler", &Replayer::createSampler}, {"createShader", &Replayer::createShader},
            {"destroyTexture", &Replayer::destroyTexture}, {"destroyBuffer", &Replayer::destroyBuffer},
            {"destroySampler", &Replayer::destroySampler}, {"destroyShader", &Replayer::destroyShader},
            {"writeBuffer", &Replayer::writeBuffer}, {"writeTexture", &Replayer::writeTexture},
            {"copyBuffer", &Replayer::copyBuffer}, {"copyTexture", &Replayer::copyTexture},
            {"clearBuffer", &Replayer::clearBuffer}, {"clearTexture", &Replayer::clearTexture},
            {"readBuffer", &Replayer::readBuffer}, {"requestReadback", &Replayer::requestReadback},
            {"readTexture", &Replayer::readTexture}, {"dispatch", &Replayer::dispatch},
            {"dispatchIndirect", &Replayer::dispatchIndirect}, {"draw", &Replayer::draw},
            {"drawIndexed", &Replayer::drawIndexed}, {"drawIndirect", &Replayer::drawIndirect},
            {"beginMarker", &Replayer::beginMarker}, {"endMarker", &Replayer::endMarker},
            {"setTimingEnabled", &Replayer::setTimingEnabled}, {"setTimingDepth", &Replayer::setTimingDepth},
            {"endFrame", &Replayer::endFrame}, {"waitIdle", &Replayer::waitIdle},
        };
        auto it = handlers.find(call);
        if (it == handlers.end()) throw DecodeError("call: unknown call '" + call.substr(0, 64) + "'");
        try {
            return (this->*it->second)(f);
        } catch (const OverBudget& e) {
            throw OverBudget(call + ": " + e.what());
        } catch (const DecodeError& e) {
            throw DecodeError(call + ": " + e.what());
        }
    }

private:
    TextureHandle texture(const Fields& f, const char* key) { return ctx_.map<TextureHandle>(ctx_.textures, f.at(key), f.path(key)); }
    BufferHandle buffer(const Fields& f, const char* key) { return ctx_.map<BufferHandle>(ctx_.buffers, f.at(key), f.path(key)); }
    // Optional payload: absent or empty is no data (the recorded call passed null).
    const std::vector<uint8_t>* data(const Fields& f) {
        if (!f.has("data")) return nullptr;
        const std::vector<uint8_t>& bytes = ctx_.bytes(f.at("data"), f.path("data"));
        return bytes.empty() ? nullptr : &bytes;
    }
    // The recorded id of a created object (read before the call: a bad one must stop the line before the
    // device is called) and, after the call, the live id it stands for.
    static void remember(std::unordered_map<uint32_t, uint32_t>& map, uint32_t recorded, uint32_t id) {
        if (recorded) map[recorded] = id;
    }
    // The scratch a read-back line needs, within ReplayOptions::maxReadBytes.
    std::vector<uint8_t> scratch(uint64_t bytes, const std::string& field) {
        if (bytes > options_.maxReadBytes)
            throw DecodeError(field + ": a read of " + std::to_string(bytes) + " bytes exceeds the limit of " +
                              std::to_string(options_.maxReadBytes) + " bytes (ReplayOptions::maxReadBytes)");
        return std::vector<uint8_t>(size_t(bytes));
    }

    bool createTexture(const Fields& f) {
        const uint32_t result = f.u32("result");
        const TextureDesc desc = record::decodeTextureDesc(f.object("desc"));
        const std::vector<uint8_t>* initial = data(f);
        // The device reads the whole initial data the description implies: it must be exactly there.
        if (initial) {
            const auto need = sizes::textureBytes(desc);
            if (!need || *need != initial->size())
                throw DecodeError("data: " + std::to_string(initial->size()) + " bytes, but the description needs " +
                                  (need ? std::to_string(*need) : std::string("a size that cannot be computed")));
        }
        notLive(liveTextures_, result, "texture");
        const uint64_t bytes = sizes::textureBytes(desc).value_or(0);  // 0: the device refuses the description
        reserveBytes(bytes, "texture");
        // A wrapped native texture cannot be replayed elsewhere: an ordinary texture stands in for it.
        const TextureHandle h = device_.createTexture(desc, initial ? initial->data() : nullptr);
        remember(ctx_.textures, result, h.id);
        if (h && result) liveTextures_[result] = {lineNumber_, bytes}, addLiveBytes(bytes);
        return bool(h);
    }
    bool createBuffer(const Fields& f) {
        const uint32_t result = f.u32("result");
        const BufferDesc desc = record::decodeBufferDesc(f.object("desc"));
        const std::vector<uint8_t>* initial = data(f);
        if (initial && initial->size() != desc.size)
            throw DecodeError("data: " + std::to_string(initial->size()) + " bytes, but desc.size is " + std::to_string(desc.size));
        notLive(liveBuffers_, result, "buffer");
        reserveBytes(desc.size, "buffer");
        const BufferHandle h = device_.createBuffer(desc, initial ? initial->data() : nullptr);
        remember(ctx_.buffers, result, h.id);
        if (h && result) liveBuffers_[result] = {lineNumber_, desc.size}, addLiveBytes(desc.size);
        return bool(h);
    }
    bool createSampler(const Fields& f) {
        const uint32_t result = f.u32("result");
        const SamplerDesc desc = record::decodeSamplerDesc(f.object("desc"));
        notLive(liveSamplers_, result, "sampler");
        const SamplerHandle h = device_.createSampler(desc);
        remember(ctx_.samplers, result, h.id);
        if (h && result) liveSamplers_[result] = {lineNumber_, 0};
        return bool(h);
    }
    bool createShader(const Fields& f) {
        const uint32_t result = f.u32("result");
        ShaderDesc desc;
        const std::string& name = f.string("blob");
        desc.debugName = f.string("debugName");
        // An empty name is a recorded call with a null blob, which fails again; any other name must be here.
        if (!name.empty() && !(desc.blob = findShader(name.c_str())))
            throw DecodeError("blob: shader '" + name.substr(0, 128) + "' is not embedded in this program");
        notLive(liveShaders_, result, "shader");
        const ShaderHandle h = device_.createShader(desc);
        remember(ctx_.shaders, result, h.id);
        if (h && result) liveShaders_[result] = {lineNumber_, 0}, shaderBlobs_[h.id] = desc.blob;
        return bool(h);
    }
    bool destroyTexture(const Fields& f) { return device_.destroy(texture(f, "handle")), forget(liveTextures_, f), true; }
    bool destroyBuffer(const Fields& f) { return device_.destroy(buffer(f, "handle")), forget(liveBuffers_, f), true; }
    bool destroySampler(const Fields& f) {
        return device_.destroy(ctx_.map<SamplerHandle>(ctx_.samplers, f.at("handle"), f.path("handle"))), forget(liveSamplers_, f), true;
    }
    bool destroyShader(const Fields& f) {
        const ShaderHandle h = ctx_.map<ShaderHandle>(ctx_.shaders, f.at("handle"), f.path("handle"));
        shaderBlobs_.erase(h.id);
        return device_.destroy(h), forget(liveShaders_, f), true;
    }

    bool writeBuffer(const Fields& f) {
        // Decoded into locals first: as arguments of one call, `data.size()` was read before the payload was
        // decoded (the order of evaluation is unspecified), and every replayed write had size 0.
        const BufferHandle b = buffer(f, "buffer");
        const uint64_t offset = f.u64("offset");
        const std::vector<uint8_t>* bytes = data(f);
        uint64_t size = bytes ? bytes->size() : 0;
        if (f.has("size")) {  // recordings before the size was written have only the data
            const uint64_t recorded = f.u64("size");
            if (bytes && recorded != size)
                throw DecodeError("size: " + std::to_string(recorded) + ", but data holds " + std::to_string(size) + " bytes");
            size = recorded;  // without data: the recorded call passed null with this size, and fails again
        }
        return device_.writeBuffer(b, offset, bytes ? bytes->data() : nullptr, size);
    }
    bool writeTexture(const Fields& f) {
        const TextureHandle t = texture(f, "texture");
        const TextureSubresource sub = decodeSub(f, "sub");
        const std::vector<uint8_t>* bytes = data(f);
        // The device reads the whole subresource from the pointer: the data must cover exactly that.
        if (bytes) {
            if (const TextureDesc* d = device_.describe(t)) {
                const auto need = sizes::subresourceBytes(*d, sub);
                if (need && *need != bytes->size())
                    throw DecodeError("data: " + std::to_string(bytes->size()) + " bytes, but the subresource holds " +
                                      std::to_string(*need));
            }
        }
        return device_.writeTexture(t, sub, bytes ? bytes->data() : nullptr);
    }
    bool copyBuffer(const Fields& f) {
        const BufferHandle dst = buffer(f, "dst"), src = buffer(f, "src");
        const uint64_t dstOffset = f.u64("dstOffset"), srcOffset = f.u64("srcOffset"), size = f.u64("size");
        return device_.copyBuffer(dst, dstOffset, src, srcOffset, size);
    }
    bool copyTexture(const Fields& f) {
        const TextureHandle dst = texture(f, "dst"), src = texture(f, "src");
        const TextureSubresource dstSub = decodeSub(f, "dstSub"), srcSub = decodeSub(f, "srcSub");
        return device_.copyTexture(dst, dstSub, src, srcSub);
    }
    bool clearBuffer(const Fields& f) {
        const BufferHandle b = buffer(f, "buffer");
        const BufferRange range{f.u64("offset"), f.u64("size")};
        const uint32_t value = f.u32("value");
        return device_.clearBuffer(b, range, value);
    }
    bool clearTexture(const Fields& f) {
        const TextureHandle t = texture(f, "texture");
        const uint32_t baseMip = f.u32("baseMip"), mipCount = f.u32("mipCount");
        const json& v = f.tuple("value", 4);
        ClearValue value;
        for (size_t i = 0; i < 4; ++i)
            value.u[i] = uint32_t(record::readUnsigned(v[i], UINT32_MAX, "value[" + std::to_string(i) + "]", "uint32"));
        return device_.clearTexture(t, baseMip, mipCount, value);
    }
    // Polls (pollReadback is not recorded) happen after each endFrame and waitIdle, when the device has had
    // its chance to finish the copies; each result lands in scratch memory of the requested size.
    bool requestReadback(const Fields& f) {
        const BufferHandle b = buffer(f, "buffer");
        const uint64_t offset = f.u64("offset"), size = f.u64("size");
        if (size > options_.maxReadBytes) scratch(size, f.path("size"));  // refused before the device copies
        const uint64_t ticket = device_.requestReadback(b, offset, size);
        if (ticket) pendingReadbacks_.emplace_back(ticket, size);
        return ticket != 0;
    }
    void pollReadbacks() {
        std::vector<std::pair<uint64_t, uint64_t>> stillPending;
        for (const auto& [ticket, size] : pendingReadbacks_) {
            std::vector<uint8_t> out(static_cast<size_t>(size));
            if (device_.pollReadback(ticket, out.data()) == ReadbackStatus::Pending) stillPending.emplace_back(ticket, size);
        }
        pendingReadbacks_ = std::move(stillPending);
    }
    bool readBuffer(const Fields& f) {
        const BufferHandle b = buffer(f, "buffer");
        const uint64_t offset = f.u64("offset"), size = f.u64("size");
        std::vector<uint8_t> out = scratch(size, f.path("size"));
        return device_.readBuffer(b, offset, size, out.data());
    }
    bool readTexture(const Fields& f) {
        const TextureHandle t = texture(f, "texture");
        const TextureSubresource sub = decodeSub(f, "sub");
        const TextureDesc* d = device_.describe(t);
        const auto need = d ? sizes::subresourceBytes(*d, sub) : std::nullopt;
        // Outside the texture (or no texture): the device refuses; it gets a valid pointer all the same.
        std::vector<uint8_t> out = scratch(need ? *need : 16, f.path("sub"));
        return device_.readTexture(t, sub, out.data());
    }

    bool dispatch(const Fields& f) {
        const DispatchState s = record::decodeDispatch(f.object("state"), ctx_);
        const json& g = f.tuple("groups", 3);
        uint32_t groups[3];
        for (size_t i = 0; i < 3; ++i)
            groups[i] = uint32_t(record::readUnsigned(g[i], UINT32_MAX, "groups[" + std::to_string(i) + "]", "uint32"));
        checkDispatchWork(s, groups, "groups");
        return device_.dispatch(s, groups[0], groups[1], groups[2]);
    }
    bool dispatchIndirect(const Fields& f) {
        const DispatchState s = record::decodeDispatch(f.object("state"), ctx_);
        const BufferHandle args = buffer(f, "args");
        const uint64_t offset = f.u64("offset");
        DispatchIndirectArgs a{};
        if (readIndirect(args, offset, &a, sizeof a)) {
            const uint32_t groups[3] = {a.x, a.y, a.z};
            checkDispatchWork(s, groups, "the argument buffer's groups");
        }
        return device_.dispatchIndirect(s, args, offset);
    }
    bool draw(const Fields& f) {
        const DrawCallState s = record::decodeDraw(f.object("state"), ctx_);
        const json& a = f.tuple("args", 4);
        uint32_t v[4];
        for (size_t i = 0; i < 4; ++i) v[i] = uint32_t(record::readUnsigned(a[i], UINT32_MAX, "args[" + std::to_string(i) + "]", "uint32"));
        checkDrawWork(v[0], v[1], "vertices", "args");
        return device_.draw(s, DrawArgs{v[0], v[1], v[2], v[3]});
    }
    bool drawIndexed(const Fields& f) {
        const DrawCallState s = record::decodeDraw(f.object("state"), ctx_);
        const json& a = f.tuple("args", 5);
        auto u = [&](size_t i) { return uint32_t(record::readUnsigned(a[i], UINT32_MAX, "args[" + std::to_string(i) + "]", "uint32")); };
        const DrawIndexedArgs args{u(0), u(1), u(2), int32_t(record::readSigned(a[3], INT32_MIN, INT32_MAX, "args[3]", "int32")), u(4)};
        checkDrawWork(args.indexCount, args.instanceCount, "indices", "args");
        return device_.drawIndexed(s, args);
    }
    bool drawIndirect(const Fields& f) {
        const DrawCallState s = record::decodeDraw(f.object("state"), ctx_);
        const BufferHandle args = buffer(f, "args");
        const uint64_t offset = f.u64("offset");
        const bool indexed = f.boolean("indexed");
        DrawIndexedArgs a{};  // DrawArgs' first two fields are the same counts
        if (readIndirect(args, offset, &a, indexed ? sizeof(DrawIndexedArgs) : sizeof(DrawArgs)))
            checkDrawWork(a.indexCount, a.instanceCount, indexed ? "indices" : "vertices", "the argument buffer");
        return device_.drawIndirect(s, args, offset, indexed);
    }

    bool beginMarker(const Fields& f) {
        const std::string& label = f.string("label");
        if (openMarkers_ >= options_.maxMarkerDepth)
            throw OverBudget("a marker opened inside " + std::to_string(openMarkers_) + " open ones, more than the budget of " +
                             std::to_string(options_.maxMarkerDepth) + " (ReplayOptions::maxMarkerDepth; an endMarker missing?)");
        ++openMarkers_;
        return device_.beginMarker(label.c_str()), true;
    }
    bool endMarker(const Fields&) {
        if (openMarkers_) --openMarkers_;
        return device_.endMarker(), true;
    }
    bool setTimingEnabled(const Fields& f) { return device_.setTimingEnabled(f.boolean("enabled")), true; }
    bool setTimingDepth(const Fields& f) { return device_.setTimingDepth(f.u32("depth")), true; }
    bool endFrame(const Fields&) { return device_.endFrame(), pollReadbacks(), true; }
    bool waitIdle(const Fields&) { return device_.waitIdle(), pollReadbacks(), true; }

    // A recorded result id that is still live may not be created again: every later line naming it would be
    // ambiguous. (An id destroyed earlier may be: an engine's RHI may reuse ids.)
    struct LiveObject {
        uint64_t line = 0;   // where it was created
        uint64_t bytes = 0;  // textures and buffers: what it counts against maxLiveBytes
    };
    void notLive(const std::unordered_map<uint32_t, LiveObject>& live, uint32_t result, const char* kind) const {
        auto it = live.find(result);
        if (it != live.end())
            throw DecodeError("result: " + std::string(kind) + " #" + std::to_string(result) + " is already live (created at line " +
                              std::to_string(it->second.line) + " and not destroyed since)");
    }
    void forget(std::unordered_map<uint32_t, LiveObject>& live, const Fields& f) {
        auto it = live.find(uint32_t(record::readUnsigned(f.at("handle"), UINT32_MAX, f.path("handle"), "handle id")));
        if (it == live.end()) return;
        liveBytes_ = liveBytes_ == UINT64_MAX ? UINT64_MAX : liveBytes_ - it->second.bytes;  // saturated: stays so
        live.erase(it);
    }
    void addLiveBytes(uint64_t bytes) {
        if (__builtin_add_overflow(liveBytes_, bytes, &liveBytes_)) liveBytes_ = UINT64_MAX;
    }
    void reserveBytes(uint64_t bytes, const char* kind) const {
        if (options_.maxLiveBytes == UINT64_MAX) return;  // no budget (liveBytes_ may have saturated)
        if (bytes > options_.maxLiveBytes || liveBytes_ > options_.maxLiveBytes - bytes)
            throw OverBudget("a " + std::string(kind) + " of " + std::to_string(bytes) + " bytes with " + std::to_string(liveBytes_) +
                             " bytes already live exceeds the budget of " + std::to_string(options_.maxLiveBytes) +
                             " bytes (ReplayOptions::maxLiveBytes)");
    }
    void checkDispatchWork(const DispatchState& s, const uint32_t groups[3], const std::string& what) const {
        auto blob = shaderBlobs_.find(s.shader.id);
        if (blob == shaderBlobs_.end() || !blob->second) return;  // no such shader: the device refuses the call
        const uint32_t* local = blob->second->reflection.localSize;
        const uint64_t invocations = saturatingProduct({groups[0], groups[1], groups[2], local[0], local[1], local[2]});
        if (invocations > options_.maxDispatchInvocations)
            throw OverBudget(what + ": " + std::to_string(groups[0]) + " x " + std::to_string(groups[1]) + " x " + std::to_string(groups[2]) +
                             " groups of " + std::to_string(uint64_t(local[0]) * local[1] * local[2]) + " invocations (" +
                             (invocations == UINT64_MAX ? std::string("more than 2^64") : std::to_string(invocations)) +
                             ") exceed the budget of " + std::to_string(options_.maxDispatchInvocations) +
                             " invocations per dispatch (ReplayOptions::maxDispatchInvocations)");
    }
    void checkDrawWork(uint32_t count, uint32_t instances, const char* unit, const std::string& what) const {
        const uint64_t work = uint64_t(count) * instances;
        if (work > options_.maxDrawVertices)
            throw OverBudget(what + ": " + std::to_string(count) + " " + unit + " x " + std::to_string(instances) + " instances (" +
                             std::to_string(work) + ") exceed the budget of " + std::to_string(options_.maxDrawVertices) +
                             " per draw (ReplayOptions::maxDrawVertices)");
    }
    // An indirect call's arguments as the GPU will read them; false when they cannot be read (the device then
    // refuses the call itself) or the budget is not to be applied.
    bool readIndirect(BufferHandle args, uint64_t offset, void* out, uint64_t size) {
        if (!options_.boundIndirectWork) return false;
        const BufferDesc* d = device_.describe(args);
        if (!d || !sizes::rangeInside(offset, size, d->size)) return false;
        return device_.readBuffer(args, offset, size, out);
    }

    IDevice& device_;
    const ReplayOptions& options_;
    DecodeContext ctx_;
    uint64_t lineNumber_ = 0;
    std::unordered_map<uint32_t, LiveObject> liveTextures_, liveBuffers_, liveSamplers_, liveShaders_;  // by recorded id
    std::unordered_map<uint32_t, const ShaderBlob*> shaderBlobs_;                                     // by live id
    uint64_t liveBytes_ = 0;
    uint32_t openMarkers_ = 0;
    std::vector<std::pair<uint64_t, uint64_t>> pendingReadbacks_;  // ticket, size
};

// Runs the replay; any exception ends it with `*message` set (the caller adds the line).
bool replayStream(std::istream& in, IDevice& device, const ReplayOptions& options, ReplayStats& stats,
                  uint64_t& lineNumber, std::string* message) {
    Replayer replayer(device, options);
    std::string line;
    for (;;) {
        ++lineNumber;  // before reading: a stream that throws mid-line is reported at that line
        const LineStatus status = readLine(in, &line, options.maxLineBytes);
        if (status == LineStatus::End) return --lineNumber, true;
        if (status == LineStatus::TooLong) {
            *message = "longer than the limit of " + std::to_string(options.maxLineBytes) +
                       " bytes (ReplayOptions::maxLineBytes)";
            return false;
        }
        if (blank(line)) continue;
        if (countJsonValues(line) > options.maxJsonValues) {
            *message = "more than " + std::to_string(options.maxJsonValues) +
                       " JSON values on one line (ReplayOptions::maxJsonValues)";
            return false;
        }
        const json j = json::parse(line, nullptr, false);
        if (j.is_discarded()) {
            *message = "not valid JSON";
            return false;
        }
        try {
            const bool accepted = replayer.replay(j, lineNumber);
            ++stats.calls;
            if (!accepted) {
                if (!stats.failedCalls) stats.firstFailedLine = lineNumber;
                ++stats.failedCalls;
                if (options.onFailedCall) options.onFailedCall(lineNumber, j.at("call").get<std::string>());
            }
        } catch (const OverBudget& e) {
            *message = e.what();
            stats.overBudget = true;
            return false;
        } catch (const DecodeError& e) {
            *message = e.what();
            return false;
        }
    }
}
}  // namespace

bool replayRecording(std::istream& in, IDevice& device, const ReplayOptions& options, ReplayStats* stats,
                     std::string* error) {
    ReplayStats local;
    uint64_t lineNumber = 0;
    std::string message;
    bool ok = false;
    // The API boundary: nothing thrown below — std::bad_alloc, std::length_error, an exception of the
    // device, of the stream or of a callback — leaves replayRecording.
    try {
        ok = replayStream(in, device, options, local, lineNumber, &message);
    } catch (const std::bad_alloc&) {
        message = "out of memory (std::bad_alloc)";
    } catch (const std::exception& e) {
        message = std::string("exception: ") + e.what();
    } catch (...) {
        message = "unknown exception";
    }
    if (!ok && error) {
        try {
            *error = "recording line " + std::to_string(lineNumber) + ": " + message;
        } catch (...) {
            // Out of memory for the message itself: the false return still says it failed.
        }
    }
    if (stats) *stats = local;
    return ok;
}

bool replayRecording(std::istream& in, IDevice& device, ReplayStats* stats, std::string* error) {
    return replayRecording(in, device, ReplayOptions{}, stats, error);
}

}  // namespace bricklight::rhi
