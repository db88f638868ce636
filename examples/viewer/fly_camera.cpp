#include "fly_camera.h"

#include <algorithm>
#include <cmath>

namespace bricklight::viewer {

namespace {
constexpr float kRadiansPerPixel = 0.004f;
constexpr float kMaxPitch = 1.55f;  // just short of straight up or down, where yaw is undefined
}  // namespace

void FlyCamera::reset(const scenes::Camera& camera, float sceneSize) {
    base_ = camera;
    eye_ = camera.eye;
    const glm::vec3 d = camera.at - camera.eye;
    const float length = glm::length(d);
    const glm::vec3 f = length > 0.0f ? d / length : glm::vec3(0.0f, 0.0f, -1.0f);
    yaw_ = std::atan2(f.x, -f.z);
    // Clamped as mouse look clamps it: straight up or down the fly basis (forward × up) would be zero.
    pitch_ = std::clamp(std::asin(std::clamp(f.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
    distance_ = length > 0.0f ? length : 1.0f;
    target_ = eye_ + f * distance_;
    speed_ = std::max(sceneSize, 1e-3f) * 0.25f;
    moved_ = false;
}

glm::vec3 FlyCamera::forward() const {
    return {std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), -std::cos(pitch_) * std::cos(yaw_)};
}

void FlyCamera::setMode(Mode mode) {
    if (mode == Mode::Orbit) target_ = eye_ + forward() * distance_;
    mode_ = mode;
}

bool FlyCamera::update(const CameraInput& in) {
    bool moved = false;
    if (in.look != glm::vec2(0.0f)) {
        yaw_ += in.look.x * kRadiansPerPixel;
        pitch_ = std::clamp(pitch_ - in.look.y * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
        moved = true;
    }
    if (mode_ == Mode::Orbit) {
        if (in.scroll != 0.0f) {
            distance_ = std::max(distance_ * std::pow(0.9f, in.scroll), 1e-3f);
            moved = true;
        }
        eye_ = target_ - forward() * distance_;
        moved_ = moved_ || moved;
        return moved;
    }
    if (in.scroll != 0.0f) speed_ = std::clamp(speed_ * std::pow(1.25f, in.scroll), 1e-4f, 1e6f);
    if (in.move != glm::vec3(0.0f)) {
        const glm::vec3 f = forward();
        const glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0.0f, 1.0f, 0.0f)));
        const glm::vec3 step = right * in.move.x + glm::vec3(0.0f, 1.0f, 0.0f) * in.move.y + f * in.move.z;
        eye_ += step * speed_ * in.seconds * (in.fast ? 4.0f : 1.0f);
        moved = true;
    }
    moved_ = moved_ || moved;
    return moved;
}

scenes::Camera FlyCamera::camera() const {
    if (!moved_) return base_;
    scenes::Camera c = base_;
    c.eye = eye_;
    c.at = eye_ + forward() * distance_;
    c.up = glm::vec3(0.0f, 1.0f, 0.0f);
    return c;
}

}  // namespace bricklight::viewer
