// Work that may crash, hang or eat memory on hostile input (assimp's readers), run in a child process
// with limits, so that the caller gets an error instead of losing the process:
//   - fork(); the child resets the fatal signals to their default action (a crash is seen as the signal,
//     also under sanitizers or libFuzzer), writes no core file, may grow its address space by at most
//     `memoryBytes` over what it inherited (RLIMIT_AS; not under AddressSanitizer, whose shadow memory
//     needs the address space), dies with the parent, runs `work` and sends its bytes through a pipe;
//   - the parent waits at most `timeoutSeconds`, reads at most `maxReplyBytes` (growing its buffer only as
//     bytes arrive), kills the child when its resident memory grows by more than `memoryBytes` (the
//     bound that also holds under AddressSanitizer), and names what happened: "<what> crashed (signal 11,
//     Segmentation fault)", "<what> timed out after 60 s", "<what> exceeded the memory limit of N MiB".
// fork() copies only the calling thread: call this before starting threads that hold locks the work
// needs (bricklight-render loads its scene before it creates a device). Available on Linux; elsewhere
// kIsolationAvailable is false and callers run the work in their own process, unprotected.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace bricklight::scenes {

#if defined(__linux__)
constexpr bool kIsolationAvailable = true;
#else
constexpr bool kIsolationAvailable = false;
#endif

struct IsolationLimits {
    std::string what = "the work";  // for messages: "the model importer"
    double timeoutSeconds = 60.0;
    uint64_t memoryBytes = 4ull << 30;
    uint64_t maxReplyBytes = 1ull << 30;
    std::string timeoutHint, memoryHint;  // appended to those messages: how to raise the limit
};

// True with `reply` holding what `work` returned; false with `error` if the child crashed, timed out,
// exceeded its memory, threw, or sent a reply that is too long or cut short.
bool runIsolated(const std::function<std::vector<uint8_t>()>& work, const IsolationLimits& limits, std::vector<uint8_t>* reply,
                 std::string* error);

}  // namespace bricklight::scenes
