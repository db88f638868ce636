// JSON form of the RHI records, shared by the recording device and the replayer. Handles are written as
// their ids; the replayer maps them to the ids its device issues.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <unordered_map>
#include <vector>

#include "bricklight/rhi.h"

namespace bricklight::rhi::record {

using nlohmann::json;

std::string base64Encode(const void* data, size_t size);
bool base64Decode(const std::string& text, std::vector<uint8_t>* out);

json encode(const TextureDesc& d);
json encode(const BufferDesc& d);
json encode(const SamplerDesc& d);
json encode(const Bindings& b);
json encode(const DispatchState& s);
json encode(const DrawCallState& s);

// Maps recorded handle ids to live ones; keeps decoded constant bytes alive for one call.
struct DecodeContext {
    std::unordered_map<uint32_t, uint32_t> textures, buffers, samplers, shaders;
    std::vector<std::vector<uint8_t>> constantStorage;
    std::vector<std::string> labels;
    std::string error;

    template <typename H>
    H map(const std::unordered_map<uint32_t, uint32_t>& m, const json& id) {
        uint32_t recorded = id.get<uint32_t>();
        if (recorded == 0) return H{};
        auto it = m.find(recorded);
        if (it == m.end()) {
            error = "handle #" + std::to_string(recorded) + " was not created in the recording";
            return H{};
        }
        return H{it->second};
    }
};

bool decode(const json& j, TextureDesc* d);
bool decode(const json& j, BufferDesc* d);
bool decode(const json& j, SamplerDesc* d);
bool decode(const json& j, DispatchState* s, DecodeContext& ctx);
bool decode(const json& j, DrawCallState* s, DecodeContext& ctx);

}  // namespace bricklight::rhi::record
