// The messages of one SdfScene or GiContext: each distinct message goes to the application's callback (or
// stderr) the first time only, and is counted every time, so that an input mistake repeated every frame
// does not flood the log and the application can still see how often it happened.
#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "bricklight/errors.h"

namespace bricklight::detail {

class DiagnosticLog {
public:
    // `prefix` names the object ("sdf 'scene': ", "gi: ") and starts every message.
    explicit DiagnosticLog(std::string prefix) : prefix_(std::move(prefix)) {}

    // Records the message, sends it to `callback` (stderr when empty) if it is new, and returns the full
    // text. Errors also become the last error.
    const std::string& report(const rhi::ErrorCallback& callback, rhi::Severity severity, ErrorCode code,
                              const std::string& message);
    const Error& lastError() const { return lastError_; }
    const std::vector<Diagnostic>& diagnostics() const { return entries_; }

private:
    // Distinct messages kept; further new ones are counted in one last entry (a caller that builds a
    // new message every call must not grow the log without bound).
    static constexpr size_t kMaxDistinct = 256;
    std::string prefix_;
    std::vector<Diagnostic> entries_;
    std::unordered_map<std::string, size_t> index_;
    Error lastError_;
};

}  // namespace bricklight::detail
