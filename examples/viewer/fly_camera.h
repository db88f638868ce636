// The viewer's camera: fly (WASD/QE to move, the mouse to look, the scroll wheel for speed) or orbit (the
// mouse turns around a target, the scroll wheel zooms). Plain maths on scenes::Camera, no window: the app
// turns GLFW input into CameraInput.
#pragma once

#include <glm/glm.hpp>

#include "scene_geometry.h"

namespace bricklight::viewer {

struct CameraInput {
    glm::vec3 move{0.0f};   // right, up, forward, each -1..1 (WASD, QE)
    glm::vec2 look{0.0f};   // mouse movement in pixels while looking (right, down)
    float scroll = 0.0f;    // wheel steps (up: positive)
    float seconds = 0.0f;   // since the last update
    bool fast = false;      // shift held: 4x speed
};

class FlyCamera {
public:
    enum class Mode { Fly, Orbit };
    // Starts at `camera`; `sceneSize` (the scene's bounds' diagonal) sets the initial speed.
    void reset(const scenes::Camera& camera, float sceneSize);
    // Applies one frame's input; true if the camera moved.
    bool update(const CameraInput& input);
    scenes::Camera camera() const;
    Mode mode() const { return mode_; }
    void setMode(Mode mode);  // orbit turns around the point the camera looks at, at its current distance
    float speed() const { return speed_; }  // world units per second (fly)

private:
    glm::vec3 forward() const;
    scenes::Camera base_;
    glm::vec3 eye_{0.0f}, target_{0.0f};
    float yaw_ = 0.0f, pitch_ = 0.0f;  // radians; yaw 0 looks along -z
    float speed_ = 1.0f, distance_ = 1.0f;
    Mode mode_ = Mode::Fly;
    // Until the first move camera() is exactly the camera reset() was given (not rebuilt from yaw and pitch),
    // so that an untouched view is bricklight-render's to the bit.
    bool moved_ = false;
};

}  // namespace bricklight::viewer
