// The work and memory a recording may ask for (ReplayOptions' budgets, issue 35): a line past one stops the
// replay before the device is called, naming the line, what it asks for and the budget; nothing is dropped
// silently. Each case edits one line of the valid session (replay_test_support.h).
#include <catch2/catch.hpp>

#include "replay_test_support.h"

using namespace bricklight::rhi;
using namespace bricklight::testing;

namespace {

uint32_t resultNamed(const std::vector<json>& lines, const std::string& debugName) {
    for (const json& l : lines)
        if (l.contains("desc") && l["desc"].contains("debugName") && l["desc"]["debugName"] == debugName) return l["result"].get<uint32_t>();
    FAIL("no object named " << debugName);
    return 0;
}

ReplayResult replayLines(const std::vector<json>& lines, const ReplayOptions& options = {}, bool validate = true) {
    return replayText(joinLines(lines), validate, options);
}

void checkStoppedOverBudget(const ReplayResult& r, size_t lineIndex, const std::string& message) {
    INFO(r.error);
    CHECK_FALSE(r.threw);
    CHECK(r.seconds < kReplaySecondsBound);
    CHECK_FALSE(r.ok);
    CHECK(r.stats.overBudget);
    CHECK(r.error == "recording line " + std::to_string(lineIndex + 1) + ": " + message);
}

}  // namespace

TEST_CASE("the valid session replays within the default budgets", "[replay]") {
    const ReplayResult r = replayLines(sessionLines());
    INFO(r.error);
    CHECK(r.ok);
    CHECK_FALSE(r.stats.overBudget);
    CHECK(r.stats.failedCalls == 0);
}

TEST_CASE("a dispatch past the invocation budget stops the replay, also when its groups come from a buffer", "[replay]") {
    std::vector<json> lines = sessionLines();
    const size_t at = lineOf(lines, "dispatch");
    lines[at]["groups"] = {65535, 65535, 1};
    checkStoppedOverBudget(replayLines(lines), at,
                           "dispatch: groups: 65535 x 65535 x 1 groups of 64 invocations (274869518400) exceed the budget of 268435456 "
                           "invocations per dispatch (ReplayOptions::maxDispatchInvocations)");
    lines[at]["groups"] = {65535, 65535, 65535};  // more than the devices' 2^32 count: was run as nothing, silently
    checkStoppedOverBudget(replayLines(lines), at,
                           "dispatch: groups: 65535 x 65535 x 65535 groups of 64 invocations (18013573888344000) exceed the budget of "
                           "268435456 invocations per dispatch (ReplayOptions::maxDispatchInvocations)");
    ReplayOptions raised;
    raised.maxDispatchInvocations = UINT64_MAX;  // raised: the null device runs nothing, so it goes through
    CHECK(replayLines(lines, raised).ok);

    // The indirect dispatch reads [65535, 65535, 1] from its argument buffer, written just before it.
    lines = sessionLines();
    const size_t indirect = lineOf(lines, "dispatchIndirect");
    lines.insert(lines.begin() + long(indirect), json{{"call", "writeBuffer"}, {"buffer", resultNamed(lines, "args")}, {"offset", 0},
                                                     {"size", 12}, {"data", "//8AAP//AAABAAAA"}});
    auto null = createNullDevice();
    BufferMemoryDevice memory(*null);
    auto validated = createValidationDevice(memory);
    const ReplayResult r = replayOn(*validated, joinLines(lines));
    checkStoppedOverBudget(r, indirect + 1,
                           "dispatchIndirect: the argument buffer's groups: 65535 x 65535 x 1 groups of 64 invocations (274869518400) "
                           "exceed the budget of 268435456 invocations per dispatch (ReplayOptions::maxDispatchInvocations)");
}

TEST_CASE("a draw past the vertex budget stops the replay", "[replay]") {
    std::vector<json> lines = sessionLines();
    const size_t at = lineOf(lines, "draw");
    lines[at]["args"] = {4294967295u, 1, 0, 0};
    checkStoppedOverBudget(replayLines(lines), at,
                           "draw: args: 4294967295 vertices x 1 instances (4294967295) exceed the budget of 268435456 per draw "
                           "(ReplayOptions::maxDrawVertices)");
    lines[at]["args"] = {3, 4294967295u, 0, 0};
    checkStoppedOverBudget(replayLines(lines), at,
                           "draw: args: 3 vertices x 4294967295 instances (12884901885) exceed the budget of 268435456 per draw "
                           "(ReplayOptions::maxDrawVertices)");
    lines = sessionLines();
    const size_t indexed = lineOf(lines, "drawIndexed");
    lines[indexed]["args"] = {65536, 65536, 0, 0, 0};
    checkStoppedOverBudget(replayLines(lines), indexed,
                           "drawIndexed: args: 65536 indices x 65536 instances (4294967296) exceed the budget of 268435456 per draw "
                           "(ReplayOptions::maxDrawVertices)");
}

TEST_CASE("textures and buffers past the memory budget stop the replay; destroyed ones give their bytes back", "[replay]") {
    const json huge = {{"call", "createBuffer"}, {"result", 9000}, {"desc", {{"size", 2ull << 30}, {"structStride", 0}, {"usage", 1}, {"debugName", "huge"}}}};
    checkStoppedOverBudget(replayLines({huge}), 0,
                           "createBuffer: a buffer of 2147483648 bytes with 0 bytes already live exceeds the budget of 1073741824 "
                           "bytes (ReplayOptions::maxLiveBytes)");
    // 600 MB twice exceeds 1 GiB; with the first destroyed in between, it does not.
    const json big = {{"call", "createBuffer"}, {"result", 9001}, {"desc", {{"size", 600000000}, {"structStride", 0}, {"usage", 1}, {"debugName", "big"}}}};
    json second = big;
    second["result"] = 9002;
    const ReplayResult twice = replayLines({big, second});
    checkStoppedOverBudget(twice, 1,
                           "createBuffer: a buffer of 600000000 bytes with 600000000 bytes already live exceeds the budget of 1073741824 "
                           "bytes (ReplayOptions::maxLiveBytes)");
    const ReplayResult inTurn = replayLines({big, json{{"call", "destroyBuffer"}, {"handle", 9001}}, second});
    INFO(inTurn.error);
    CHECK(inTurn.ok);
}

TEST_CASE("markers past the depth budget stop the replay", "[replay]") {
    std::vector<json> lines;
    for (int i = 0; i < 40; ++i) lines.push_back({{"call", "beginMarker"}, {"label", "deep"}});
    for (bool validate : {true, false})
        checkStoppedOverBudget(replayLines(lines, {}, validate), 32,
                               "beginMarker: a marker opened inside 32 open ones, more than the budget of 32 "
                               "(ReplayOptions::maxMarkerDepth; an endMarker missing?)");
}

TEST_CASE("a result id that is still live is not created again; one destroyed may be", "[replay]") {
    std::vector<json> lines = sessionLines();
    const size_t at = lineOf(lines, "createBuffer");
    lines.insert(lines.begin() + long(at) + 1, lines[at]);
    const ReplayResult r = replayLines(lines);
    INFO(r.error);
    CHECK_FALSE(r.ok);
    CHECK_FALSE(r.stats.overBudget);
    CHECK(r.error == "recording line " + std::to_string(at + 2) + ": createBuffer: result: buffer #" +
                         std::to_string(lines[at]["result"].get<uint32_t>()) + " is already live (created at line " +
                         std::to_string(at + 1) + " and not destroyed since)");
    const json buffer = {{"call", "createBuffer"}, {"result", 5}, {"desc", {{"size", 16}, {"structStride", 0}, {"usage", 1}, {"debugName", "again"}}}};
    const ReplayResult reused = replayLines({buffer, json{{"call", "destroyBuffer"}, {"handle", 5}}, buffer});
    INFO(reused.error);
    CHECK(reused.ok);
}
