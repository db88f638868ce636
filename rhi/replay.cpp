// Replays a recording (JSON lines from the recording device) on any IDevice.
#include <istream>

#include "bricklight/rhi_validation.h"
#include "record_json.h"

namespace bricklight::rhi {

namespace {
using record::json;

TextureSubresource subOf(const json& j) { return TextureSubresource{j[0], j[1], j[2]}; }

// Executes one recorded call; returns false with ctx.error set when the line cannot be understood.
bool replayLine(const json& j, IDevice& device, record::DecodeContext& ctx, bool* callFailed) {
    const std::string call = j.at("call");
    std::vector<uint8_t> data;
    auto bytes = [&](const char* key) {
        if (j.contains(key)) record::base64Decode(j.at(key).get<std::string>(), &data);
        return data.empty() ? nullptr : data.data();
    };
    auto tex = [&](const char* key) { return ctx.map<TextureHandle>(ctx.textures, j.at(key)); };
    auto buf = [&](const char* key) { return ctx.map<BufferHandle>(ctx.buffers, j.at(key)); };
    bool ok = true;
    if (call == "createTexture" || call == "wrapNativeTexture") {
        TextureDesc d;
        record::decode(j.at("desc"), &d);
        TextureHandle h = device.createTexture(d, bytes("data"));
        ok = bool(h);
        ctx.textures[j.at("result")] = h.id;
    } else if (call == "createBuffer" || call == "wrapNativeBuffer") {
        BufferDesc d;
        record::decode(j.at("desc"), &d);
        BufferHandle h = device.createBuffer(d, bytes("data"));
        ok = bool(h);
        ctx.buffers[j.at("result")] = h.id;
    } else if (call == "createSampler") {
        SamplerDesc d;
        record::decode(j.at("desc"), &d);
        SamplerHandle h = device.createSampler(d);
        ok = bool(h);
        ctx.samplers[j.at("result")] = h.id;
    } else if (call == "createShader") {
        ShaderDesc d;
        std::string name = j.at("blob");
        d.blob = findShader(name.c_str());
        d.debugName = j.at("debugName");
        if (!d.blob) {
            ctx.error = "shader '" + name + "' is not embedded in this program";
            return false;
        }
        ShaderHandle h = device.createShader(d);
        ok = bool(h);
        ctx.shaders[j.at("result")] = h.id;
    } else if (call == "destroyTexture") {
        device.destroy(tex("handle"));
    } else if (call == "destroyBuffer") {
        device.destroy(buf("handle"));
    } else if (call == "destroySampler") {
        device.destroy(ctx.map<SamplerHandle>(ctx.samplers, j.at("handle")));
    } else if (call == "destroyShader") {
        device.destroy(ctx.map<ShaderHandle>(ctx.shaders, j.at("handle")));
    } else if (call == "writeBuffer") {
        ok = device.writeBuffer(buf("buffer"), j.at("offset"), bytes("data"), data.size());
    } else if (call == "writeTexture") {
        ok = device.writeTexture(tex("texture"), subOf(j.at("sub")), bytes("data"));
    } else if (call == "copyBuffer") {
        ok = device.copyBuffer(buf("dst"), j.at("dstOffset"), buf("src"), j.at("srcOffset"), j.at("size"));
    } else if (call == "copyTexture") {
        ok = device.copyTexture(tex("dst"), subOf(j.at("dstSub")), tex("src"), subOf(j.at("srcSub")));
    } else if (call == "clearBuffer") {
        ok = device.clearBuffer(buf("buffer"), BufferRange{j.at("offset"), j.at("size")}, j.at("value"));
    } else if (call == "clearTexture") {
        ClearValue v;
        for (int i = 0; i < 4; ++i) v.u[i] = j.at("value")[i];
        ok = device.clearTexture(tex("texture"), j.at("baseMip"), j.at("mipCount"), v);
    } else if (call == "readBuffer") {
        std::vector<uint8_t> scratch(j.at("size").get<uint64_t>());
        ok = device.readBuffer(buf("buffer"), j.at("offset"), scratch.size(), scratch.data());
    } else if (call == "requestReadback") {
        // Replayed as a blocking read so that the copy happens at the same point of the stream.
        std::vector<uint8_t> scratch(j.at("size").get<uint64_t>());
        ok = device.readBuffer(buf("buffer"), j.at("offset"), scratch.size(), scratch.data());
    } else if (call == "readTexture") {
        TextureHandle t = tex("texture");
        const TextureDesc* d = device.describe(t);
        std::vector<uint8_t> scratch(d ? subresourceBytes(*d, subOf(j.at("sub"))) : 0);
        ok = d && device.readTexture(t, subOf(j.at("sub")), scratch.data());
    } else if (call == "dispatch" || call == "dispatchIndirect") {
        DispatchState s;
        if (!record::decode(j.at("state"), &s, ctx)) return false;
        if (call == "dispatch") {
            const json& g = j.at("groups");
            ok = device.dispatch(s, g[0], g[1], g[2]);
        } else {
            ok = device.dispatchIndirect(s, buf("args"), j.at("offset"));
        }
    } else if (call == "draw" || call == "drawIndexed" || call == "drawIndirect") {
        DrawCallState s;
        if (!record::decode(j.at("state"), &s, ctx)) return false;
        if (call == "draw") {
            const json& a = j.at("args");
            ok = device.draw(s, DrawArgs{a[0], a[1], a[2], a[3]});
        } else if (call == "drawIndexed") {
            const json& a = j.at("args");
            ok = device.drawIndexed(s, DrawIndexedArgs{a[0], a[1], a[2], a[3], a[4]});
        } else {
            ok = device.drawIndirect(s, buf("args"), j.at("offset"), j.at("indexed"));
        }
    } else if (call == "beginMarker") {
        device.beginMarker(j.at("label").get<std::string>().c_str());
    } else if (call == "endMarker") {
        device.endMarker();
    } else if (call == "setTimingEnabled") {
        device.setTimingEnabled(j.at("enabled"));
    } else if (call == "setTimingDepth") {
        device.setTimingDepth(j.at("depth"));
    } else if (call == "endFrame") {
        device.endFrame();
    } else if (call == "waitIdle") {
        device.waitIdle();
    } else {
        ctx.error = "unknown call '" + call + "'";
        return false;
    }
    *callFailed = !ok;
    return ctx.error.empty();
}

}  // namespace

bool replayRecording(std::istream& in, IDevice& device, ReplayStats* stats, std::string* error) {
    record::DecodeContext ctx;
    std::string line;
    uint64_t lineNumber = 0;
    ReplayStats local;
    while (std::getline(in, line)) {
        ++lineNumber;
        if (line.empty()) continue;
        json j = json::parse(line, nullptr, false);
        bool callFailed = false;
        bool understood = !j.is_discarded() && j.is_object() && j.contains("call");
        if (understood) {
            try {
                understood = replayLine(j, device, ctx, &callFailed);
            } catch (const json::exception& e) {
                ctx.error = e.what();
                understood = false;
            }
        } else {
            ctx.error = "not a JSON object with a \"call\" field";
        }
        if (!understood) {
            if (error) *error = "recording line " + std::to_string(lineNumber) + ": " + ctx.error;
            if (stats) *stats = local;
            return false;
        }
        ++local.calls;
        if (callFailed) ++local.failedCalls;
        ctx.constantStorage.clear();
        ctx.labels.clear();
    }
    if (stats) *stats = local;
    return true;
}

}  // namespace bricklight::rhi
