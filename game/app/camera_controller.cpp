#include "game/app/camera_controller.h"

#include <algorithm>

namespace rtrt {
namespace {

vec3 DirectionOf(float yaw, float pitch) {
    return vec3(-std::sin(yaw) * std::cos(pitch), std::sin(pitch),
                -std::cos(yaw) * std::cos(pitch));
}

}  // namespace

CameraController::CameraController(const Camera& start, float speed) : speed_(speed) {
    Reset(start);
}

void CameraController::Reset(const Camera& camera) {
    camera_ = camera;
    const vec3 f = glm::normalize(camera.forward);
    pitch_ = std::clamp(std::asin(std::clamp(f.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
    yaw_ = std::atan2(-f.x, -f.z);
    camera_.up = vec3(0.0f, 1.0f, 0.0f);
    target_ = camera.position + distance_ * f;
    Apply();
}

vec3 CameraController::Forward() const { return DirectionOf(yaw_, pitch_); }

void CameraController::SetTarget(vec3 target) {
    target_ = target;
    distance_ = std::max(glm::length(camera_.position - target), 1e-3f);
    const vec3 f = glm::normalize(target - camera_.position);
    pitch_ = std::clamp(std::asin(std::clamp(f.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
    yaw_ = std::atan2(-f.x, -f.z);
    Apply();
}

void CameraController::SetMode(Mode mode) {
    if (mode == Mode::kOrbit && mode_ != Mode::kOrbit)
        target_ = camera_.position + distance_ * Forward();
    mode_ = mode;
    Apply();
}

void CameraController::Update(const CameraInput& in, float dt) {
    yaw_ -= in.look.x * kRadiansPerPixel;
    pitch_ = std::clamp(pitch_ - in.look.y * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
    const float step = speed_ * dt * (in.fast ? 4.0f : 1.0f);
    const vec3 forward = Forward();
    const vec3 right = glm::normalize(glm::cross(forward, vec3(0.0f, 1.0f, 0.0f)));
    const vec3 move = step * (in.move.x * right + in.move.y * vec3(0, 1, 0) + in.move.z * forward);
    if (mode_ == Mode::kFly) {
        camera_.position += move;
    } else {
        target_ += move;  // WASD pans the orbit
        distance_ = std::max(distance_ * std::pow(0.9f, in.zoom), 1e-3f);
    }
    Apply();
}

void CameraController::Apply() {
    camera_.forward = Forward();
    camera_.up = vec3(0.0f, 1.0f, 0.0f);
    if (mode_ == Mode::kOrbit) camera_.position = target_ - distance_ * camera_.forward;
}

}  // namespace rtrt
