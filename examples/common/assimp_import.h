// A model file through assimp, in the calling process: the checks of model_checks.h, the import through
// GuardedFileSystem with aiProcess_ValidateDataStructure, LoadLimits applied to what assimp built, then
// the scene (meshes, materials, texture references or embedded bytes, lights, a default camera). Nothing
// here protects the process from assimp crashing or hanging: loadModel runs this in a child process
// where it can (isolated_call.h).
#pragma once

#include <string>

#include "scene_geometry.h"

namespace bricklight::scenes {

// Empty scene and `error` ("'path': why") on failure.
SceneGeometry importModelInProcess(const std::string& path, const LoadLimits& limits, std::string* error);

}  // namespace bricklight::scenes
