// Malformed recordings: each defect class that crashed, threw or was silently truncated before is now an
// error naming the line and the field, with the lines before it replayed, nothing thrown, in bounded time.
#include <catch2/catch.hpp>

#include <functional>

#include "replay_test_support.h"

using namespace bricklight::rhi;
using namespace bricklight::testing;

namespace {

struct Mutation {
    const char* call;     // the first session line with this call is changed
    const char* pointer;  // JSON pointer of the member to set ("" = the whole line)
    json value;           // its new value; a discarded json removes the member
    std::string needle;   // the error must contain it
};

// Applies `m` to the session, replays it, and checks that the replay stops at exactly that line, with
// "recording line N: <needle>", after replaying the lines before it, within the time bound.
void expectLineError(const Mutation& m) {
    std::vector<json> lines = sessionLines();
    const size_t index = lineOf(lines, m.call);
    json& line = lines[index];
    if (*m.pointer == 0) {
        line = m.value;
    } else if (m.value.is_discarded()) {
        const json::json_pointer p(m.pointer);
        line.at(p.parent_pointer()).erase(p.back());
    } else {
        line[json::json_pointer(m.pointer)] = m.value;
    }
    INFO("line " << index + 1 << ": " << line.dump().substr(0, 300));
    for (bool validate : {true, false}) {
        const ReplayResult r = replayText(joinLines(lines), validate);
        INFO("error: " << r.error);
        CHECK_FALSE(r.threw);
        CHECK_FALSE(r.ok);
        CHECK(r.error.rfind("recording line " + std::to_string(index + 1) + ": ", 0) == 0);
        CHECK(r.error.find(m.needle) != std::string::npos);
        CHECK(r.stats.calls == index);  // every line before it ran
        CHECK(r.seconds < kReplaySecondsBound);
    }
}

void expectAll(const std::vector<Mutation>& mutations) {
    for (const Mutation& m : mutations) {
        INFO("mutation " << m.call << " " << m.pointer << " = " << m.value.dump());
        expectLineError(m);
    }
}

const json kRemove = json(json::value_t::discarded);

}  // namespace

TEST_CASE("the session replays with every call accepted", "[replay]") {
    const ReplayResult r = replayText(joinLines(sessionLines()));
    INFO(r.error);
    for (const auto& e : r.deviceErrors) UNSCOPED_INFO(e);
    REQUIRE(r.ok);
    CHECK(r.stats.calls == sessionLines().size());
    CHECK(r.stats.failedCalls == 0);
    CHECK(r.deviceErrors.empty());
}

// The SIGSEGV class: an empty array where a fixed-length one belongs was indexed anyway.
TEST_CASE("empty and short arrays are errors naming the field", "[replay]") {
    const json empty = json::array();
    expectAll({
        {"dispatch", "/groups", empty, "dispatch: groups: expected 3 elements, got 0"},
        {"dispatch", "/groups", {1, 2}, "groups: expected 3 elements, got 2"},
        {"draw", "/args", empty, "draw: args: expected 4 elements, got 0"},
        {"drawIndexed", "/args", {3, 1, 0, 0}, "drawIndexed: args: expected 5 elements, got 4"},
        {"draw", "/state/colorTargets/0/blend", empty, "state.colorTargets[0].blend: expected 8 elements, got 0"},
        {"draw", "/state/colorTargets/0/clearColor", empty, "state.colorTargets[0].clearColor: expected 4 elements"},
        {"draw", "/state/scissor", empty, "state.scissor: expected 4 elements, got 0"},
        {"draw", "/state/viewport", empty, "state.viewport: expected 6 elements, got 0"},
        {"draw", "/state/depth", empty, "state.depth: expected 3 elements, got 0"},
        {"draw", "/state/raster", empty, "state.raster: expected 5 elements, got 0"},
        {"clearTexture", "/value", empty, "clearTexture: value: expected 4 elements, got 0"},
        {"writeTexture", "/sub", empty, "writeTexture: sub: expected 3 elements, got 0"},
        {"copyTexture", "/srcSub", empty, "copyTexture: srcSub: expected 3 elements, got 0"},
        {"readTexture", "/sub", {0, 0, 0, 0}, "readTexture: sub: expected 3 elements, got 4"},
    });
}

TEST_CASE("lists longer than the record holds are errors, not silently cut", "[replay]") {
    std::vector<json> lines = sessionLines();
    const json texture = lines[lineOf(lines, "dispatch")]["state"]["bindings"]["textures"][0];
    json seventeen = json::array();
    for (int i = 0; i < 17; ++i) seventeen.push_back(texture);
    json five = json::array();
    for (int i = 0; i < 5; ++i) five.push_back({{"slot", i}, {"data", "AAAAAA=="}});
    expectAll({
        {"dispatch", "/state/bindings/textures", seventeen, "state.bindings.textures: 17 entries exceed the capacity of 16"},
        {"dispatch", "/state/bindings/constants", five, "state.bindings.constants: 5 entries exceed the capacity of 4"},
    });
}

TEST_CASE("fields of the wrong type or missing are errors naming the field", "[replay]") {
    expectAll({
        {"createTexture", "/desc/width", "16", "createTexture: desc.width: expected a whole number (uint32), got a string"},
        {"createTexture", "/desc/height", 1.5, "desc.height: expected a whole number (uint32), got the number 1.5"},
        {"createTexture", "/desc/debugName", 5, "desc.debugName: expected a string, got the number 5"},
        {"createTexture", "/desc/format", "RGBA9_UNORM", "desc.format: 'RGBA9_UNORM' is not a format name"},
        {"createTexture", "/desc/height", kRemove, "createTexture: desc.height: missing"},
        {"createBuffer", "/desc", json::array(), "createBuffer: desc: expected an object, got an array"},
        {"createSampler", "/desc/minLod", "zero", "desc.minLod: expected a number (or \"inf\", \"-inf\", \"nan\"), got a string"},
        {"createSampler", "/desc/compareEnable", 1, "desc.compareEnable: expected true or false, got the number 1"},
        {"createShader", "/blob", nullptr, "createShader: blob: expected a string, got null"},
        {"dispatch", "/state", "probe", "dispatch: state: expected an object, got a string"},
        {"dispatch", "/state/bindings/textures", json::object(), "state.bindings.textures: expected an array, got an object"},
        {"dispatch", "/state/label", 5, "state.label: expected a string, got the number 5"},
        {"dispatch", "/state/bindings/readBuffers/0/range", 64, "state.bindings.readBuffers[0].range: expected an object"},
        {"draw", "/state/depth/0", 1, "state.depth[0]: expected true or false, got the number 1"},
        {"draw", "/state/viewport/2", true, "state.viewport[2]: expected a number, got a boolean"},
        {"drawIndirect", "/indexed", "yes", "drawIndirect: indexed: expected true or false, got a string"},
        {"beginMarker", "/label", json::array(), "beginMarker: label: expected a string, got an array"},
        {"endFrame", "/call", 7, "call: expected a string, got the number 7"},
        {"endFrame", "/call", "present", "call: unknown call 'present'"},
        {"endFrame", "", json::array({1, 2}), "line: expected an object, got an array"},
        {"endFrame", "", json::object(), "call: missing"},
    });
}

// Numbers were converted with nlohmann's get<T>, which truncates: 300 became a mip of 44.
TEST_CASE("numbers that do not fit their field are errors, not truncated", "[replay]") {
    expectAll({
        {"dispatch", "/state/bindings/textures/0/view/baseMip", 300, "state.bindings.textures[0].view.baseMip: 300 does not fit uint8 (0..255)"},
        {"dispatch", "/state/bindings/textures/0/view/layerCount", 65536, "view.layerCount: 65536 does not fit uint16 (0..65535)"},
        {"dispatch", "/state/bindings/textures/0/slot", 256, "state.bindings.textures[0].slot: 256 does not fit uint8"},
        {"dispatch", "/state/flags", -1, "state.flags: -1 does not fit uint32 (0..4294967295)"},
        {"dispatch", "/groups/0", 4294967296ull, "groups[0]: 4294967296 does not fit uint32"},
        {"createTexture", "/desc/width", 4294967296ull, "desc.width: 4294967296 does not fit uint32 (0..4294967295)"},
        {"createTexture", "/desc/dimension", 4, "desc.dimension: 4 does not fit enum value (0..3)"},
        {"createTexture", "/result", 4294967296ull, "result: 4294967296 does not fit uint32"},
        {"createBuffer", "/desc/size", -1, "desc.size: -1 does not fit uint64"},
        {"createBuffer", "/desc/size", 1.8446744073709552e19, "desc.size: expected a whole number (uint64), got the number"},
        {"createSampler", "/desc/maxLod", 1e39, "desc.maxLod: 1e+39 does not fit a float"},
        {"createSampler", "/desc/addressU", 4, "desc.addressU: 4 does not fit enum value (0..3)"},
        {"dispatch", "/state/bindings/storageBuffers/0/access", 4, "storageBuffers[0].access: 4 does not fit enum value (0..3)"},
        {"draw", "/state/scissor/0", -2147483649ll, "state.scissor[0]: -2147483649 does not fit int32 (-2147483648..2147483647)"},
        {"draw", "/state/colorTargets/0/blend/1", 10, "state.colorTargets[0].blend[1]: 10 does not fit BlendFactor (0..9)"},
        {"draw", "/state/colorTargets/0/blend/7", 256, "state.colorTargets[0].blend[7]: 256 does not fit uint8"},
        {"drawIndexed", "/args/3", 2147483648ll, "args[3]: 2147483648 does not fit int32"},
        {"clearTexture", "/value/2", 4294967296ull, "value[2]: 4294967296 does not fit uint32"},
        {"setTimingDepth", "/depth", 4294967296ull, "setTimingDepth: depth: 4294967296 does not fit uint32"},
    });
}

TEST_CASE("handles that no earlier line created are errors", "[replay]") {
    expectAll({
        {"dispatch", "/state/shader", 999, "dispatch: state.shader: handle #999 was not created in the recording"},
        {"writeBuffer", "/buffer", 77, "writeBuffer: buffer: handle #77 was not created in the recording"},
        {"draw", "/state/colorTargets/0/view/texture", 123456, "state.colorTargets[0].view.texture: handle #123456"},
    });
}

TEST_CASE("payloads that are not base64, or not the size the call reads, are errors", "[replay]") {
    expectAll({
        {"createBuffer", "/data", "@@@@", "createBuffer: data: not canonical base64 (4 characters)"},
        {"writeBuffer", "/data", "AAA", "writeBuffer: data: not canonical base64 (3 characters)"},
        {"writeBuffer", "/data", "AA=A", "data: not canonical base64"},
        {"writeBuffer", "/data", 12, "data: expected a string, got the number 12"},
        {"dispatch", "/state/bindings/constants/0/data", "A", "state.bindings.constants[0].data: not canonical base64"},
        // Initial data must be exactly what the description implies: the device reads all of it.
        {"createTexture", "/data", "AAAA", "createTexture: data: 3 bytes, but the description needs 1280"},
        {"createBuffer", "/data", "AAAA", "createBuffer: data: 3 bytes, but desc.size is 256"},
        {"writeTexture", "/data", "AAAA", "writeTexture: data: 3 bytes, but the subresource holds 256"},
        {"writeBuffer", "/size", 41, "writeBuffer: size: 41, but data holds 40 bytes"},
    });
}

TEST_CASE("truncated and broken lines are errors naming the line", "[replay]") {
    std::vector<json> lines = sessionLines();
    for (size_t i = 0; i < lines.size(); ++i) {
        const std::string whole = lines[i].dump();
        for (size_t cut : {size_t(1), whole.size() / 2, whole.size() - 1}) {
            std::string text;
            for (size_t k = 0; k < i; ++k) text += lines[k].dump() + "\n";
            text += whole.substr(0, cut) + "\n" + whole + "\n";
            INFO("line " << i + 1 << " cut to " << cut << " characters");
            const ReplayResult r = replayText(text);
            CHECK_FALSE(r.threw);
            CHECK_FALSE(r.ok);
            CHECK(r.error == "recording line " + std::to_string(i + 1) + ": not valid JSON");
            CHECK(r.stats.calls == i);
        }
    }
    // A last line without its newline is a whole line; blank lines and CRLF endings are fine.
    std::string text = joinLines(lines);
    text.pop_back();
    text = "\n  \r\n" + text;
    const ReplayResult r = replayText(text);
    INFO(r.error);
    CHECK(r.ok);
    CHECK(r.stats.calls == lines.size());
    const ReplayResult crlf = replayText("{\"call\":\"endFrame\"}\r\n{\"call\":\"waitIdle\"}\r\n");
    CHECK(crlf.ok);
    CHECK(crlf.stats.calls == 2);
    const ReplayResult binary = replayText(std::string("{\"call\":\"endFrame\"}\n\0\xff{\n", 24));
    CHECK(binary.error == "recording line 2: not valid JSON");
}
