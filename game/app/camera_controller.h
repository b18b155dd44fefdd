#pragma once
// The window's camera: fly (WASD moves, the mouse looks around) or orbit (the mouse turns the
// camera around a target point, the wheel changes the distance). Yaw and pitch are kept rather
// than the forward vector, so that looking never rolls the camera and pitch stops short of the
// poles, where the up vector would become undefined.
#include "engine/render_rt/camera.h"

namespace rtrt {

struct CameraInput {
    vec3 move{0.0f};    // -1..1 along right, up, forward (WASD, Q/E)
    vec2 look{0.0f};    // mouse movement in pixels (right, down)
    float zoom = 0.0f;  // wheel steps, positive = closer
    bool fast = false;  // shift: 4x speed
};

class CameraController {
  public:
    enum class Mode { kFly, kOrbit };

    // speed: units per second when flying (the window derives it from the scene's size).
    CameraController(const Camera& start, float speed);

    void SetMode(Mode mode);
    Mode GetMode() const { return mode_; }
    // Orbit mode turns around this point; entering orbit mode puts it ahead of the camera.
    void SetTarget(vec3 target);
    void Update(const CameraInput& input, float dt);
    // Takes over a camera set from outside (a scene's camera path) without a jump.
    void Reset(const Camera& camera);

    const Camera& Get() const { return camera_; }
    vec3 Forward() const;

    static constexpr float kRadiansPerPixel = 0.0025f;
    static constexpr float kMaxPitch = 1.55f;  // about 89 degrees

  private:
    void Apply();

    Camera camera_;
    Mode mode_ = Mode::kFly;
    float speed_;
    float yaw_ = 0.0f, pitch_ = 0.0f;  // yaw 0 looks down -z, pitch 0 level
    vec3 target_{0.0f};
    float distance_ = 10.0f;
};

}  // namespace rtrt
