// What one line may cost: huge sizes, payloads and lines are refused before anything is allocated for them,
// the validation wrapper's endless loop on a width of 2^31 is gone, and no exception leaves replayRecording.
#include <catch2/catch.hpp>

#include <sstream>
#include <stdexcept>

#include "replay_test_support.h"

using namespace bricklight::rhi;
using namespace bricklight::testing;

namespace {

std::string line(const json& j) { return j.dump() + "\n"; }

json textureLine(uint32_t result, uint32_t width, uint32_t height, uint32_t depth = 1, int dimension = 0, uint32_t mips = 1) {
    return {{"call", "createTexture"}, {"result", result},
            {"desc", {{"dimension", dimension}, {"format", "RGBA8_UNORM"}, {"width", width}, {"height", height},
                      {"depthOrLayers", depth}, {"mipLevels", mips}, {"usage", 1}, {"debugName", "hostile"}}}};
}
json bufferLine(uint32_t result, uint64_t size, uint32_t usage = 8) {
    return {{"call", "createBuffer"}, {"result", result},
            {"desc", {{"size", size}, {"structStride", 0}, {"usage", usage}, {"debugName", "hostile"}}}};
}

// These tests are about what the device refuses: past the replay's memory budget (replay_budget_tests.cpp), the
// replay would stop before the device saw the description.
ReplayOptions unlimitedMemory() {
    ReplayOptions o;
    o.maxLiveBytes = UINT64_MAX;
    return o;
}

void checkBounded(const ReplayResult& r) {
    CHECK_FALSE(r.threw);
    CHECK(r.seconds < kReplaySecondsBound);
}

}  // namespace

// The wrapper counted mips by shifting the largest extent until zero: 2^31 needed a shift by 32 (a shift by
// 0 on x86) and it never stopped.
TEST_CASE("a width or height of 2^31 or more is refused through the wrapper in bounded time", "[replay]") {
    std::string text;
    uint32_t id = 1;
    for (uint32_t big : {1u << 31, 0xFFFFFFFFu}) {
        text += line(textureLine(id++, big, 1));
        text += line(textureLine(id++, 1, big, 1, 0, 32));
        text += line(textureLine(id++, 4, 4, big, 2));                // 3D depth
        text += line(textureLine(id++, big, big, big, 1, UINT32_MAX));  // array of 2^31 layers, every mip
    }
    const ReplayResult r = replayText(text, true, unlimitedMemory());
    INFO(r.error);
    checkBounded(r);
    REQUIRE(r.ok);
    CHECK(r.stats.calls == 8);
    CHECK(r.stats.failedCalls == 8);
    REQUIRE(r.deviceErrors.size() >= 8);
    CHECK(r.deviceErrors[0].find("createTexture 'hostile': size 2147483648x1 exceeds maxTextureSize2D 16384") != std::string::npos);
}

TEST_CASE("huge buffer sizes and ranges fail as calls, never as allocations", "[replay]") {
    std::string text = line(bufferLine(1, UINT64_MAX)) + line(bufferLine(2, UINT64_MAX - 3, 1)) +
                       line(bufferLine(3, uint64_t(1) << 62)) + line(bufferLine(4, 64, 1));
    // A write of 2^64-1 bytes without data (the recorded call passed null) reaches the device as such.
    text += line({{"call", "writeBuffer"}, {"buffer", 4}, {"offset", 0}, {"size", UINT64_MAX}, {"data", ""}});
    text += line({{"call", "copyBuffer"}, {"dst", 4}, {"dstOffset", UINT64_MAX - 3}, {"src", 4}, {"srcOffset", 0}, {"size", 8}});
    text += line({{"call", "clearBuffer"}, {"buffer", 4}, {"offset", 8}, {"size", UINT64_MAX - 3}, {"value", 0}});
    text += line({{"call", "readBuffer"}, {"buffer", 4}, {"offset", UINT64_MAX}, {"size", 16}});
    for (bool validate : {true, false}) {
        const ReplayResult r = replayText(text, validate, unlimitedMemory());
        INFO("validate " << validate << ": " << r.error);
        checkBounded(r);
        REQUIRE(r.ok);
        CHECK(r.stats.calls == 8);
        CHECK(r.stats.failedCalls == (validate ? 4 : 0));  // the null device alone checks no range
    }
    // A read-back of 2^40 bytes would make the replayer allocate that much: refused before allocating.
    const ReplayResult read =
        replayText(text + line({{"call", "readBuffer"}, {"buffer", 3}, {"offset", 0}, {"size", 1ull << 40}}), true, unlimitedMemory());
    checkBounded(read);
    CHECK_FALSE(read.ok);
    CHECK(read.error == "recording line 9: readBuffer: size: a read of 1099511627776 bytes exceeds the limit of 268435456 "
                        "bytes (ReplayOptions::maxReadBytes)");
    // The same for a texture read-back, whose size comes from the live texture's description.
    Capabilities huge = createNullDevice()->capabilities();
    huge.limits.maxTextureSize2D = 1u << 20;
    auto null = createNullDevice(&huge);
    auto wrapper = createValidationDevice(*null);
    const ReplayResult texture = replayOn(*wrapper,
                                          line(textureLine(1, 1u << 20, 1u << 20)) + line({{"call", "readTexture"}, {"texture", 1}, {"sub", {0, 0, 0}}}),
                                          unlimitedMemory());
    checkBounded(texture);
    CHECK(texture.error.find("recording line 2: readTexture: sub: a read of 4398046511104 bytes exceeds the limit") == 0);
}

TEST_CASE("lines, JSON values and payloads beyond the limits are errors naming the limit", "[replay]") {
    const std::string ok = line({{"call", "endFrame"}});
    ReplayOptions small;
    small.maxLineBytes = 200;
    ReplayResult r = replayText(ok + std::string(1000, ' ') + "\n", true, small);
    checkBounded(r);
    CHECK(r.error == "recording line 2: longer than the limit of 200 bytes (ReplayOptions::maxLineBytes)");

    small = ReplayOptions{};
    small.maxJsonValues = 100;
    std::string values = "[0";
    for (int i = 0; i < 60; ++i) values += ",0";
    r = replayText(ok + ok + "{\"call\":\"endFrame\",\"x\":[" + values + "]," + values + "]]}\n", true, small);
    CHECK(r.error == "recording line 3: more than 100 JSON values on one line (ReplayOptions::maxJsonValues)");
    // Megabytes of nested arrays on one line are refused by counting, not by parsing them.
    r = replayText("{\"call\":\"endFrame\",\"x\":" + std::string(4 << 20, '[') + "\n");
    checkBounded(r);
    CHECK(r.error == "recording line 1: more than 1048576 JSON values on one line (ReplayOptions::maxJsonValues)");

    small = ReplayOptions{};
    small.maxDataBytes = 64;
    const std::string payload = std::string(88, 'A');  // 66 bytes
    r = replayText(line(bufferLine(1, 66)) + line({{"call", "writeBuffer"}, {"buffer", 1}, {"offset", 0}, {"data", payload}}),
                   true, small);
    CHECK(r.error == "recording line 2: writeBuffer: data: 66 bytes of data exceed the limit of 64 bytes per line "
                     "(ReplayOptions::maxDataBytes)");
    // The budget is per line, over every payload on it: constants of 16 + 3 x 600 bytes exceed 1280 (the
    // session's largest payload) at the fourth.
    std::vector<json> lines = sessionLines();
    json& dispatch = lines[lineOf(lines, "dispatch")];
    for (int slot = 1; slot < 4; ++slot)
        dispatch["state"]["bindings"]["constants"].push_back({{"slot", slot}, {"data", std::string(800, 'A')}});
    small.maxDataBytes = 1280;
    r = replayText(joinLines(lines), true, small);
    CHECK(r.error.find("dispatch: state.bindings.constants[3].data: 600 bytes of data exceed the limit of 1280 bytes per line") !=
          std::string::npos);

    small = ReplayOptions{};
    small.maxReadBytes = 32;
    r = replayText(joinLines(sessionLines()), true, small);
    CHECK(r.error.find("readBuffer: size: a read of 64 bytes exceeds the limit of 32 bytes (ReplayOptions::maxReadBytes)") !=
          std::string::npos);
}

namespace {
// Throws from createBuffer: what a device, an allocator or the standard library may do.
class ThrowingDevice : public ForwardingTestDevice {
public:
    ThrowingDevice(IDevice& inner, std::function<void()> thrower) : ForwardingTestDevice(inner), thrower_(std::move(thrower)) {}
    BufferHandle createBuffer(const BufferDesc&, const void*) override {
        thrower_();
        return {};
    }

private:
    std::function<void()> thrower_;
};

// A stream whose buffer throws after some characters, like a stream over a file that fails mid-read.
class ThrowingBuffer : public std::streambuf {
public:
    explicit ThrowingBuffer(std::string text) : text_(std::move(text)) {}

protected:
    int_type underflow() override {
        if (pos_ >= text_.size()) throw std::runtime_error("disk on fire");
        return traits_type::to_int_type(text_[pos_]);
    }
    int_type uflow() override {
        const int_type c = underflow();
        ++pos_;
        return c;
    }

private:
    std::string text_;
    size_t pos_ = 0;
};
}  // namespace

// Only json::exception was caught: std::bad_alloc and std::length_error escaped to the caller.
TEST_CASE("exceptions from the device, the allocator or the stream do not leave replayRecording", "[replay]") {
    const std::string text = line({{"call", "endFrame"}}) + line(bufferLine(1, 64));
    struct Case {
        std::function<void()> thrower;
        std::string error;
    } cases[] = {
        {[] { throw std::bad_alloc(); }, "recording line 2: out of memory (std::bad_alloc)"},
        {[] { std::vector<int> v; v.reserve(v.max_size() + 1); }, "recording line 2: exception: "},
        {[] { throw 42; }, "recording line 2: unknown exception"},
    };
    for (const Case& c : cases) {
        auto null = createNullDevice();
        ThrowingDevice device(*null, c.thrower);
        const ReplayResult r = replayOn(device, text);
        INFO(r.error);
        CHECK_FALSE(r.threw);
        CHECK_FALSE(r.ok);
        CHECK(r.error.rfind(c.error, 0) == 0);
        CHECK(r.stats.calls == 1);
    }
    ThrowingBuffer buffer(text);
    std::istream in(&buffer);
    auto null = createNullDevice();
    ReplayStats stats;
    std::string error;
    bool ok = true;
    CHECK_NOTHROW(ok = replayRecording(in, *null, &stats, &error));
    CHECK_FALSE(ok);
    CHECK(error == "recording line 3: exception: disk on fire");  // reading line 3 failed
    CHECK(stats.calls == 2);
}

TEST_CASE("the bare null device survives hostile subresources", "[replay]") {
    // Without the wrapper nothing checks the range before the null device writes the read-back: it must
    // refuse a subresource whose size cannot be computed (a mip of 40 would shift by 40).
    std::string text = line(textureLine(1, 16, 16, 4, 1));
    text += line({{"call", "readTexture"}, {"texture", 1}, {"sub", {40, 0, 0}}});
    text += line({{"call", "readTexture"}, {"texture", 1}, {"sub", {0, 3, 0xFFFFFFFFu}}});
    text += line({{"call", "writeTexture"}, {"texture", 1}, {"sub", {0, 2, 1}}, {"data", std::string(1364, 'A') + "AA=="}});  // 1024 bytes
    const ReplayResult r = replayText(text, false);
    INFO(r.error);
    checkBounded(r);
    CHECK(r.ok);
    CHECK(r.stats.calls == 4);
    CHECK(r.stats.failedCalls == 2);
}
