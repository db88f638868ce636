#include "diagnostic_log.h"

#include <cstdio>

namespace bricklight {

const char* errorCodeName(ErrorCode code) {
    switch (code) {
        case ErrorCode::None: return "None";
        case ErrorCode::InvalidArgument: return "InvalidArgument";
        case ErrorCode::InvalidHandle: return "InvalidHandle";
        case ErrorCode::MissingInput: return "MissingInput";
        case ErrorCode::WrongFormat: return "WrongFormat";
        case ErrorCode::WrongSize: return "WrongSize";
        case ErrorCode::Aliasing: return "Aliasing";
        case ErrorCode::Unsupported: return "Unsupported";
        case ErrorCode::OverBudget: return "OverBudget";
        case ErrorCode::InvalidGeometry: return "InvalidGeometry";
        case ErrorCode::InUse: return "InUse";
        case ErrorCode::DependencyDestroyed: return "DependencyDestroyed";
        case ErrorCode::DeviceFailure: return "DeviceFailure";
        case ErrorCode::InvalidState: return "InvalidState";
        case ErrorCode::CameraMismatch: return "CameraMismatch";
        case ErrorCode::SceneNotUpdated: return "SceneNotUpdated";
    }
    return "Unknown";
}

namespace detail {

const std::string& DiagnosticLog::report(const rhi::ErrorCallback& callback, rhi::Severity severity, ErrorCode code,
                                         const std::string& message) {
    std::string text = prefix_ + message;
    if (severity == rhi::Severity::Error) {
        lastError_ = {code, text};
    }
    auto found = index_.find(text);
    if (found != index_.end()) {
        ++entries_[found->second].count;
        return entries_[found->second].message;
    }
    if (entries_.size() >= kMaxDistinct) {
        if (entries_.size() == kMaxDistinct)
            entries_.push_back({ErrorCode::None, rhi::Severity::Warning, prefix_ + "further distinct messages (not kept)", 0});
        ++entries_.back().count;
        return severity == rhi::Severity::Error ? lastError_.message : entries_.back().message;
    }
    index_.emplace(text, entries_.size());
    entries_.push_back({code, severity, text, 1});
    if (callback) {
        callback(severity, text);
    } else {
        const char* tag = severity == rhi::Severity::Error ? "error" : severity == rhi::Severity::Warning ? "warning" : "info";
        std::fprintf(stderr, "bricklight %s: %s\n", tag, text.c_str());
    }
    return entries_.back().message;
}

}  // namespace detail
}  // namespace bricklight
