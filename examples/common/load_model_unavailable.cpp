// loadModel in builds without model files (Windows: assimp is not packaged for MinGW, and the importer's
// guards, a child process under time and memory limits and files opened as regular files only, are POSIX's).
// Built-in scenes work as everywhere.
#include "scene_geometry.h"

namespace bricklight::scenes {

SceneGeometry loadModel(const std::string& path, std::string* error, const LoadLimits&) {
    if (error)
        *error = "cannot load '" + path + "': this build reads no model files (the Windows build has the built-in scenes only: "
                 "assimp, which reads models, is not available for it)";
    return SceneGeometry{};
}

}  // namespace bricklight::scenes
