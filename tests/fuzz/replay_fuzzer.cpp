// libFuzzer target: record decoding and replay (rhi::replayRecording) onto the null device under the
// validation wrapper. Besides the sanitizers' findings (crash, leak, undefined behaviour, timeout, memory),
// it traps on what the API promises against:
//   - an exception leaving replayRecording, or an error that does not name its line;
//   - the calls a replay made, recorded, not replaying to the very same recording with the same counts
//     (the encoder and the decoder disagree on a field, or a decode lets through what the encoder cannot
//     write back). These replays make exactly the recorded calls (ReplayOptions::boundIndirectWork off: its
//     reads of indirect arguments would be recorded too); a third replay, with the default options, holds the
//     indirect calls to the budgets.
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <string>

#include "bricklight/rhi_validation.h"
#include "replay_fuzz_shaders.h"

namespace {

using namespace bricklight::rhi;

struct Run {
    bool ok = false;
    ReplayStats stats;
    std::string error;
    std::string recording;  // every call the replay made, as the recording device writes it
};

Run replayRecorded(const std::string& text, bool exactCalls) {
    // Small bounds: an input is at most -max_len bytes, and what a line may allocate should stay far below
    // -rss_limit_mb.
    ReplayOptions options;
    options.boundIndirectWork = !exactCalls;
    options.maxDataBytes = 1u << 20;
    options.maxReadBytes = 1u << 20;
    auto null = createNullDevice();
    auto validation = createValidationDevice(*null);
    validation->setErrorCallback([](Severity, const std::string&) {});  // refusals are expected; keep quiet
    std::ostringstream out;
    auto recorder = createRecordingDevice(*validation, out);
    std::istringstream in(text);
    Run run;
    try {
        run.ok = replayRecording(in, *recorder, options, &run.stats, &run.error);
    } catch (...) {
        std::fprintf(stderr, "replay_fuzzer: an exception left replayRecording\n");
        __builtin_trap();
    }
    run.recording = out.str();
    return run;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const bool registered = (bricklight::fuzz::registerReplayFuzzShaders(), true);
    (void)registered;
    const std::string text(reinterpret_cast<const char*>(data), size);
    const Run bounded = replayRecorded(text, false);
    const Run first = replayRecorded(text, true);
    for (const Run* run : {&bounded, &first})
        if (!run->ok && run->error.rfind("recording line ", 0) != 0) {
            std::fprintf(stderr, "replay_fuzzer: error without a line: %s\n", run->error.c_str());
            __builtin_trap();
        }
    const Run second = replayRecorded(first.recording, true);
    if (!second.ok || second.recording != first.recording || second.stats.calls != first.stats.calls ||
        second.stats.failedCalls != first.stats.failedCalls) {
        std::fprintf(stderr, "replay_fuzzer: the re-recorded calls do not replay the same (%s)\n", second.error.c_str());
        __builtin_trap();
    }
    return 0;
}
