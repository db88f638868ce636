// A few saved views per scene (keys 1-4 in the viewer): the scene's own camera first, then views picked
// for each built-in scene, or for a model file views derived from its bounds.
#pragma once

#include <string>
#include <vector>

#include "scene_geometry.h"

namespace bricklight::viewer {

struct CameraBookmark {
    std::string name;
    scenes::Camera camera;
};

std::vector<CameraBookmark> cameraBookmarks(const std::string& sceneName, const scenes::SceneGeometry& scene);

}  // namespace bricklight::viewer
