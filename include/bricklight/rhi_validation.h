// Optional RHI layers that wrap any IDevice (ours or an engine's):
//  - the validation device checks every call against the shader reflection and the capabilities and
//    forwards only calls that pass (like nvrhi::validation);
//  - the null device executes nothing and lets the checks run without a GPU;
//  - the recording device writes every call as one JSON line; replayRecording runs a recording on any
//    IDevice (another backend, a later build, an engine's RHI).
#pragma once

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
// embedded name (findShader). Returns false with `error` naming the line and the problem.
struct ReplayStats {
    uint64_t calls = 0;
    uint64_t failedCalls = 0;  // calls the device rejected
};
bool replayRecording(std::istream& in, IDevice& device, ReplayStats* stats, std::string* error);

}  // namespace bricklight::rhi
