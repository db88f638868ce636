#include "load_limits.h"

#include <cstring>

namespace bricklight::scenes {

std::string raiseHint(const char* field) {
    // bricklight-render's option for each limit (examples/render/main.cpp; examples/demo_renderer/render_options.cpp); one table, so that every
    // message and the CLI agree.
    static const struct {
        const char* field;
        const char* option;
    } options[] = {
        {"maxFileBytes", "--max-file-bytes"},       {"maxJsonBytes", "--max-json-bytes"},
        {"maxJsonDepth", "--max-json-depth"},       {"maxVertices", "--max-vertices"},
        {"maxIndices", "--max-indices"},            {"maxFaceIndices", "--max-face-indices"},
        {"maxNodes", "--max-nodes"},                {"maxNodeDepth", "--max-node-depth"},
        {"maxTexturePixels", "--max-texture-pixels"}, {"allowOutsidePaths", "--allow-outside-paths"},
        {"importTimeoutSeconds", "--import-timeout"}, {"importMemoryBytes", "--import-memory"},
    };
    for (const auto& o : options)
        if (std::strcmp(o.field, field) == 0)
            return std::string(std::strcmp(field, "allowOutsidePaths") == 0 ? "(allow it with " : "(raise it with ") + o.option +
                   ", LoadLimits::" + field + ")";
    return std::string("(LoadLimits::") + field + ")";
}

}  // namespace bricklight::scenes
