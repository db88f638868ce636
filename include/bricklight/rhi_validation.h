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
// device that supports every format for everything except what the contract excludes (R11G11B10_FLOAT
// and RGBA8_SRGB storage) and Vulkan's minimum limits.
std::unique_ptr<IDevice> createNullDevice(const Capabilities* capabilities = nullptr);

// Writes every call made on the wrapper to `out` as one JSON object per line, then forwards it to
// `inner` (not owned). Data of writes and initial data are stored (base64), so a recording is complete.
std::unique_ptr<IDevice> createRecordingDevice(IDevice& inner, std::ostream& out);

// Runs a recording on `device`, mapping recorded handles to new ones. Shaders are found by their
// embedded name (findShader). A recording is untrusted input: every field of every line is checked
// (presence, type, range; a number that does not fit its field is an error, not truncated) before the
// device is called, what one line may make the replayer allocate is bounded by ReplayOptions, and nothing
// is thrown out of replayRecording. Returns false with `error` naming the line and the problem at the first
// line that cannot be understood (the lines before it have run); true when every line was understood,
// whether or not the device accepted each call (ReplayStats counts those it refused).
struct ReplayStats {
    uint64_t calls = 0;
    uint64_t failedCalls = 0;      // calls the device rejected
    uint64_t firstFailedLine = 0;  // line of the first of them (1-based; 0 if none)
};
struct ReplayOptions {
    // Bounds on one line; a line beyond one of them is an error naming the line and the limit. The defaults
    // hold every recording our programs make (the largest lines carry initial data in base64).
    uint64_t maxLineBytes = 256ull << 20;  // characters of one line
    uint64_t maxJsonValues = 1u << 20;     // JSON values (numbers, strings, arrays, objects) on one line
    uint64_t maxDataBytes = 192ull << 20;  // decoded base64 payload of one line (initial data, writes, constants)
    uint64_t maxReadBytes = 256ull << 20;  // scratch memory one read-back line makes the replayer allocate
    // Called after each call the device refused, with the line number and the call's name.
    std::function<void(uint64_t line, const std::string& call)> onFailedCall;
};
bool replayRecording(std::istream& in, IDevice& device, const ReplayOptions& options, ReplayStats* stats,
                     std::string* error);
bool replayRecording(std::istream& in, IDevice& device, ReplayStats* stats, std::string* error);  // default options

}  // namespace bricklight::rhi
