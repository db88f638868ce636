// Optional RHI layers that wrap any IDevice (ours or an engine's):
//  - the validation device checks every call against the shader reflection and the capabilities and
//    forwards only calls that pass (like nvrhi::validation);
//  - the null device executes nothing and lets the checks run without a GPU;
//  - the recording device writes every call as one JSON line; replayRecording runs a recording on any
//    IDevice (another backend, a later build, an engine's RHI).
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>

#include "bricklight/rhi.h"

namespace bricklight::rhi {

// `inner` is not owned and must outlive the wrapper. Errors of the wrapper and of `inner` both reach the
// callback installed on the wrapper. A rejected call returns false / a null handle and changes nothing.
std::unique_ptr<IDevice> createValidationDevice(IDevice& inner);

// A device that creates handles and checks nothing; reads return zeros. `capabilities` defaults to a
// device that supports every format for everything except what the contract excludes (R11G11B10_FLOAT,
// RGB9E5_FLOAT and RGBA8_SRGB storage) and Vulkan's minimum limits.
std::unique_ptr<IDevice> createNullDevice(const Capabilities* capabilities = nullptr);

// Writes every call made on the wrapper to `out` as one JSON object per line, then forwards it to
// `inner` (not owned). Data of writes and initial data are stored (base64), so a recording is complete.
std::unique_ptr<IDevice> createRecordingDevice(IDevice& inner, std::ostream& out);

// Runs a recording on `device`, mapping recorded handles to new ones. Shaders are found by their
// embedded name (findShader). A recording is untrusted input: every field of every line is checked
// (presence, type, range; a number that does not fit its field is an error, not truncated) before the
// device is called, what one line may make the replayer allocate and the work and memory the recording asks
// of the device are bounded by ReplayOptions, a result id still live is not created again, and nothing
// is thrown out of replayRecording. Returns false with `error` naming the line and the problem at the first
// line that cannot be understood (the lines before it have run); true when every line was understood,
// whether or not the device accepted each call (ReplayStats counts those it refused).
struct ReplayStats {
    uint64_t calls = 0;
    uint64_t failedCalls = 0;      // calls the device rejected
    uint64_t firstFailedLine = 0;  // line of the first of them (1-based; 0 if none)
    bool overBudget = false;       // the replay stopped at a line past one of ReplayOptions' work or memory budgets
};
struct ReplayOptions {
    // Bounds on one line; a line beyond one of them is an error naming the line and the limit. The defaults
    // hold every recording our programs make (the largest lines carry initial data in base64).
    uint64_t maxLineBytes = 256ull << 20;  // characters of one line
    uint64_t maxJsonValues = 1u << 20;     // JSON values (numbers, strings, arrays, objects) on one line
    uint64_t maxDataBytes = 192ull << 20;  // decoded base64 payload of one line (initial data, writes, constants)
    uint64_t maxReadBytes = 256ull << 20;  // scratch memory one read-back line makes the replayer allocate
    // The work and memory a recording may ask for. A line past one stops the replay before the device is
    // called, with an error naming the line, what it asks for and the budget (ReplayStats::overBudget): work
    // is never dropped silently, and a recording cannot make the replay run for hours or take the machine's
    // memory. The defaults hold what bricklight-render records at its default settings many times over;
    // UINT64_MAX turns a budget off.
    uint64_t maxDispatchInvocations = 1ull << 28;  // one dispatch: groups x the shader's local size
    uint64_t maxDrawVertices = 1ull << 28;         // one draw: vertices (indices) x instances
    uint64_t maxLiveBytes = 1ull << 30;            // textures and buffers alive at once (their descriptions' bytes)
    uint32_t maxMarkerDepth = kMaxMarkerDepth;     // markers open at once
    // An indirect call's counts are read from its argument buffer (readBuffer, which waits for the GPU) and
    // held to the same budgets; false skips the read and leaves indirect work unbounded (a replay that must
    // make exactly the recorded calls, to record it again say).
    bool boundIndirectWork = true;
    // Called after each call the device refused, with the line number and the call's name.
    std::function<void(uint64_t line, const std::string& call)> onFailedCall;
};
bool replayRecording(std::istream& in, IDevice& device, const ReplayOptions& options, ReplayStats* stats,
                     std::string* error);
bool replayRecording(std::istream& in, IDevice& device, ReplayStats* stats, std::string* error);  // default options

}  // namespace bricklight::rhi
