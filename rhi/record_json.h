// JSON form of the RHI records, shared by the recording device and the replayer. Handles are written as
// their ids; the replayer maps them to the ids its device issues.
//
// Decoding trusts nothing: every field's presence, JSON type and range is checked against the C++ field it
// fills (a number that does not fit is an error, never truncated), fixed-size arrays must have their exact
// length, lists at most the record's capacity, and base64 payloads are measured against a budget before
// they are decoded. A failure throws DecodeError with the path of the field ("state.bindings.textures[2]
// .view.baseMip: 300 does not fit uint8 (0..255)"); the replayer turns it into an error naming the line.
#pragma once

#include <cstdint>
#include <deque>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "bricklight/rhi.h"

namespace bricklight::rhi::record {

using nlohmann::json;

// A recorded line that cannot be understood; the message names the field.
struct DecodeError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Canonical padded base64 (RFC 4648 alphabet, length a multiple of 4, '=' only as the last one or two).
std::string base64Encode(const void* data, size_t size);
// Bytes `text` decodes to, or nullopt when it is not canonical padded base64 (checked without decoding).
std::optional<size_t> base64DecodedSize(std::string_view text);
bool base64Decode(std::string_view text, std::vector<uint8_t>* out);

// Floats as JSON numbers; the non-finite ones, which JSON has no number for, as "inf", "-inf", "nan".
json encodeFloat(float f);

json encode(const TextureDesc& d);
json encode(const BufferDesc& d);
json encode(const SamplerDesc& d);
json encode(const Bindings& b);
json encode(const DispatchState& s);
json encode(const DrawCallState& s);

// Checked reads of one JSON value; `path` names it in the error.
uint64_t readUnsigned(const json& v, uint64_t max, const std::string& path, const char* typeName);
int64_t readSigned(const json& v, int64_t min, int64_t max, const std::string& path, const char* typeName);
float readFloat(const json& v, const std::string& path);
bool readBool(const json& v, const std::string& path);
const std::string& readString(const json& v, const std::string& path);
// An array of exactly `length` elements.
const json& readTuple(const json& v, size_t length, const std::string& path);

// The members of one JSON object, read with the checks above; the path of each is "<object path>.<key>".
class Fields {
public:
    Fields(const json& object, std::string path);
    bool has(const char* key) const { return object_.contains(key); }
    const json& at(const char* key) const;  // required member
    std::string path(const char* key) const { return path_.empty() ? key : path_ + "." + key; }
    Fields object(const char* key) const { return Fields(at(key), path(key)); }

    uint8_t u8(const char* key) const { return uint8_t(readUnsigned(at(key), UINT8_MAX, path(key), "uint8")); }
    uint16_t u16(const char* key) const { return uint16_t(readUnsigned(at(key), UINT16_MAX, path(key), "uint16")); }
    uint32_t u32(const char* key) const { return uint32_t(readUnsigned(at(key), UINT32_MAX, path(key), "uint32")); }
    uint64_t u64(const char* key) const { return readUnsigned(at(key), UINT64_MAX, path(key), "uint64"); }
    float f32(const char* key) const { return readFloat(at(key), path(key)); }
    bool boolean(const char* key) const { return readBool(at(key), path(key)); }
    const std::string& string(const char* key) const { return readString(at(key), path(key)); }
    // An enum written as its integer value: 0..count-1.
    template <typename E>
    E enumeration(const char* key, int count) const {
        return E(readUnsigned(at(key), uint64_t(count - 1), path(key), "enum value"));
    }
    const json& tuple(const char* key, size_t length) const { return readTuple(at(key), length, path(key)); }

private:
    const json& object_;
    std::string path_;
};

// Per-replay state: recorded handle ids mapped to live ones, and per-line storage that the decoded records
// point into (constant bytes, labels), with the budget of payload bytes one line may decode.
struct DecodeContext {
    std::unordered_map<uint32_t, uint32_t> textures, buffers, samplers, shaders;
    // Deques: records keep pointers into the elements, which must not move as more are added.
    std::deque<std::vector<uint8_t>> byteStorage;
    std::deque<std::string> labels;
    uint64_t dataBudget = 0;  // bytes this line may still decode (ReplayOptions::maxDataBytes)
    uint64_t maxDataBytes = 0;

    void startLine(uint64_t maxData) {
        byteStorage.clear();
        labels.clear();
        dataBudget = maxDataBytes = maxData;
    }
    // A recorded handle id (0 = null) to the live one; an id that no earlier line created is an error.
    template <typename H>
    H map(const std::unordered_map<uint32_t, uint32_t>& m, const json& id, const std::string& path) const {
        const uint32_t recorded = uint32_t(readUnsigned(id, UINT32_MAX, path, "handle id"));
        if (recorded == 0) return H{};
        auto it = m.find(recorded);
        if (it == m.end()) throw DecodeError(path + ": handle #" + std::to_string(recorded) + " was not created in the recording");
        return H{it->second};
    }
    // Decodes a base64 member within the line's budget; the bytes live until the next line.
    const std::vector<uint8_t>& bytes(const json& text, const std::string& path);
    const char* label(const json& v, const std::string& path);  // null or a string
};

TextureDesc decodeTextureDesc(const Fields& f);
BufferDesc decodeBufferDesc(const Fields& f);
SamplerDesc decodeSamplerDesc(const Fields& f);
DispatchState decodeDispatch(const Fields& f, DecodeContext& ctx);
DrawCallState decodeDraw(const Fields& f, DecodeContext& ctx);

}  // namespace bricklight::rhi::record
