#include "camera_bookmarks.h"

#include <algorithm>

namespace bricklight::viewer {

namespace {

scenes::Camera look(const scenes::Camera& base, glm::vec3 eye, glm::vec3 at) {
    scenes::Camera c = base;
    c.eye = eye;
    c.at = at;
    c.up = glm::vec3(0.0f, 1.0f, 0.0f);
    return c;
}

}  // namespace

std::vector<CameraBookmark> cameraBookmarks(const std::string& sceneName, const scenes::SceneGeometry& scene) {
    std::vector<CameraBookmark> marks{{"scene camera", scene.camera}};
    const glm::vec3 lo = scene.boundsMin, hi = scene.boundsMax, centre = 0.5f * (lo + hi), size = hi - lo;
    const scenes::Camera& base = scene.camera;
    if (sceneName == "cornell") {
        // Millimetres: the box spans 556 x 548.8 x 559.2, open at z = 0, where the scene's camera looks in.
        marks.push_back({"near the floor", look(base, {278.0f, 60.0f, 40.0f}, {278.0f, 120.0f, 400.0f})});
        marks.push_back({"under the light", look(base, {100.0f, 450.0f, 100.0f}, {400.0f, 548.0f, 330.0f})});
        marks.push_back({"tall block", look(base, {450.0f, 200.0f, 80.0f}, {185.0f, 150.0f, 350.0f})});
        return marks;
    }
    // Any other scene: from above a corner, from the side at eye height, and straight down.
    marks.push_back({"overview", look(base, centre + glm::vec3(0.6f, 0.5f, 0.6f) * size, centre)});
    marks.push_back({"side", look(base, centre + glm::vec3(-0.45f * size.x, -0.2f * size.y, 0.0f), centre)});
    // Not exactly vertical (a flat scene has size.y = 0): a view straight down has no "up".
    const float reach = std::max(glm::length(size), 1e-3f);
    marks.push_back({"top", look(base, centre + glm::vec3(0.0f, 0.6f * size.y + 0.5f * reach, 0.05f * reach), centre)});
    return marks;
}

}  // namespace bricklight::viewer
