// Recordings replayed on the real backends: the session of replay_test_support (every call the recorder
// writes, each valid), recorded on the null device, replays on Vulkan and GL under the validation wrapper
// with every call accepted and no message at all (the Vulkan validation layer and synchronization
// validation on); and a recording made on one backend replays on the other.
#include <sstream>

#include "backend_test.h"
#include "replay_test_support.h"

using namespace bricklight;
using namespace bricklight::rhi;
using namespace bricklight::testing;

namespace {

void replayOnBackend(const std::string& backend, const std::string& text, size_t lines) {
    TestDevice t = makeDevice(backend);
    REQUIRE(t.device);
    std::istringstream in(text);
    ReplayStats stats;
    std::string error;
    t.device->setErrorCallback([&t](Severity s, const std::string& m) {
        if (s != Severity::Info) t.messages->push_back(m);
    });
    const bool ok = replayRecording(in, *t.device, &stats, &error);
    t.device->waitIdle();
    INFO(error);
    REQUIRE(ok);
    CHECK(stats.calls == lines);
    CHECK(stats.failedCalls == 0);
    REQUIRE_NO_MESSAGES(t);
}

void sessionReplays(const std::string& backend) {
    const std::vector<json> lines = sessionLines();
    replayOnBackend(backend, joinLines(lines), lines.size());
}

// Recorded on this backend (as the renderer's --record does), replayed on the other one and on the null device.
void recordingCrossesBackends(const std::string& backend) {
    std::stringstream text;
    {
        TestDevice t = makeDevice(backend);
        REQUIRE(t.device);
        auto recorder = createRecordingDevice(*t.device, text);
        runSession(*recorder);
        t.device->waitIdle();
        REQUIRE_NO_MESSAGES(t);
    }
    const std::string recording = text.str();
    const size_t lines = size_t(std::count(recording.begin(), recording.end(), '\n'));
    const ReplayResult null = replayText(recording);
    INFO(null.error);
    CHECK(null.ok);
    CHECK(null.stats.failedCalls == 0);
#if defined(BRICKLIGHT_HAS_VULKAN) && defined(BRICKLIGHT_HAS_GL)
    replayOnBackend(backend == "vulkan" ? "gl" : "vulkan", recording, lines);
#endif
    replayOnBackend(backend, recording, lines);
}

}  // namespace

BACKEND_TEST("replay: the recorded session replays with every call accepted", "[replay]", sessionReplays)
BACKEND_TEST("replay: a recording made on a backend replays on the others", "[replay]", recordingCrossesBackends)
