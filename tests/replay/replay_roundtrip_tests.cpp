// Replays that must reproduce the recorded calls exactly: buffer contents after writes (every replayed
// writeBuffer had size 0), and record -> replay -> record giving the same text, non-finite floats included.
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

#include "replay_test_support.h"

using namespace bricklight::rhi;
using namespace bricklight::testing;

namespace {

std::string rerecord(const std::string& text, ReplayResult* result) {
    auto null = createNullDevice();
    auto validation = createValidationDevice(*null);
    std::stringstream out;
    auto recorder = createRecordingDevice(*validation, out);
    // Exactly the recorded calls: without the read of indirect arguments the budgets add (boundIndirectWork).
    ReplayOptions exact;
    exact.boundIndirectWork = false;
    *result = replayOn(*recorder, text, exact);
    return out.str();
}

}  // namespace

// The payload was decoded while the size argument was read (the order of evaluation of function arguments
// is unspecified): g++ read data.size() first, and every replayed writeBuffer wrote nothing.
TEST_CASE("replayed writes, copies and clears leave the buffers as recorded", "[replay]") {
    auto originalNull = createNullDevice();
    BufferMemoryDevice original(*originalNull);
    auto validation = createValidationDevice(original);
    std::stringstream recording;
    {
        auto recorder = createRecordingDevice(*validation, recording);
        runSession(*recorder);
    }
    // The session destroys its buffers at the end; replay up to there and compare with a second run of the
    // session stopped at the same point.
    std::string text;
    for (std::string l; std::getline(recording, l);) {
        if (json::parse(l).at("call").get<std::string>().rfind("destroy", 0) == 0) break;
        text += l + "\n";
    }
    auto replayNull = createNullDevice();
    BufferMemoryDevice replayed(*replayNull);
    const ReplayResult r = replayOn(replayed, text);
    INFO(r.error);
    REQUIRE(r.ok);
    CHECK(r.stats.failedCalls == 0);

    auto referenceNull = createNullDevice();
    BufferMemoryDevice reference(*referenceNull);
    {
        // The same calls without the destroys: the session on a device that ignores buffer destruction.
        struct KeepBuffers : ForwardingTestDevice {
            using ForwardingTestDevice::ForwardingTestDevice;
            using ForwardingTestDevice::destroy;
            void destroy(BufferHandle) override {}
        } keep(reference);
        runSession(keep);
    }
    // Ids are issued in call order by fresh null devices, so the same id names the same buffer in both.
    for (uint32_t id = 1; id < 40; ++id) {
        const std::vector<uint8_t>* want = reference.contents(BufferHandle{id});
        if (!want) continue;
        const BufferDesc* desc = replayed.describe(BufferHandle{id});
        INFO("buffer #" << id << " '" << (desc ? desc->debugName : std::string("?")) << "'");
        const std::vector<uint8_t>* got = replayed.contents(BufferHandle{id});
        REQUIRE(got);
        CHECK(*got == *want);
    }
    // And the write did change the weights: bytes 16..55 hold the update, not the initial pattern.
    BufferHandle weights;
    for (uint32_t id = 1; id < 40 && !weights; ++id)
        if (const BufferDesc* d = replayed.describe(BufferHandle{id}); d && d->debugName == "weights") weights = BufferHandle{id};
    REQUIRE(weights);
    const std::vector<uint8_t>& bytes = *replayed.contents(weights);
    CHECK(bytes[16] == uint8_t(9));
    CHECK(bytes[55] == uint8_t(9 + 39 * 7));
    CHECK(bytes[56] == uint8_t(3 + 56 * 7));

    // A recording from before writeBuffer lines carried "size" replays the same.
    std::vector<json> withoutSize;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) {
        json j = json::parse(l);
        if (j["call"] == "writeBuffer") j.erase("size");
        withoutSize.push_back(j);
    }
    auto againNull = createNullDevice();
    BufferMemoryDevice again(*againNull);
    REQUIRE(replayOn(again, joinLines(withoutSize)).ok);
    CHECK(*again.contents(weights) == bytes);
}

TEST_CASE("record, replay, record again gives the same recording", "[replay]") {
    const std::string first = joinLines(sessionLines());
    ReplayResult r;
    const std::string second = rerecord(first, &r);
    INFO(r.error);
    REQUIRE(r.ok);
    CHECK(r.stats.failedCalls == 0);
    CHECK(second == first);
}

// JSON has no number for inf or nan (nlohmann wrote null, which no decoder could read back): the recorder
// writes them as strings.
TEST_CASE("non-finite floats survive a round trip", "[replay]") {
    std::vector<json> lines = sessionLines();
    json& sampler = lines[lineOf(lines, "createSampler")];
    sampler["desc"]["maxLod"] = "inf";
    sampler["desc"]["mipLodBias"] = 0.125;
    json& draw = lines[lineOf(lines, "draw")];
    draw["state"]["colorTargets"][0]["clearColor"] = {"nan", "-inf", 0.5, 1.0};
    const std::string first = joinLines(lines);
    ReplayResult r;
    const std::string second = rerecord(first, &r);
    INFO(r.error);
    REQUIRE(r.ok);
    CHECK(second == first);

    auto null = createNullDevice();
    std::stringstream out;
    auto recorder = createRecordingDevice(*null, out);
    SamplerDesc s;
    s.minLod = -INFINITY;
    s.maxLod = INFINITY;
    s.mipLodBias = NAN;
    recorder->createSampler(s);
    const json desc = json::parse(out.str())["desc"];
    CHECK(desc["minLod"] == "-inf");
    CHECK(desc["maxLod"] == "inf");
    CHECK(desc["mipLodBias"] == "nan");
}

// JSON is UTF-8, names need not be: the recorder threw nlohmann's type_error out of createBuffer.
TEST_CASE("names that are not UTF-8 are recorded, not thrown", "[replay]") {
    auto null = createNullDevice();
    std::stringstream out;
    auto recorder = createRecordingDevice(*null, out);
    BufferDesc b;
    b.size = 16;
    b.debugName = "caf\xe9";  // Latin-1
    BufferHandle h;
    REQUIRE_NOTHROW(h = recorder->createBuffer(b));
    CHECK(h);
    const ReplayResult r = replayText(out.str());
    CHECK(r.ok);
    CHECK(json::parse(out.str())["desc"]["debugName"] == "caf\xef\xbf\xbd");  // U+FFFD
}
