#include "viewer_backend.h"

#include <cstdio>

namespace bricklight::viewer {

rhi::ErrorCallback ViewerBackend::callbackOrStderr(const rhi::ErrorCallback& callback) {
    if (callback) return callback;
    return [](rhi::Severity, const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); };
}

}  // namespace bricklight::viewer
