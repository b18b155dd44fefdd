// The window's camera: movement along the view, looking without roll, pitch clamped short of the
// poles, orbit at a fixed distance around its target.
#include "game/app/camera_controller.h"

#include <gtest/gtest.h>

namespace rtrt {
namespace {

constexpr float kEps = 1e-5f;

void ExpectNear(vec3 a, vec3 b, float eps = kEps) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

TEST(CameraController, StartsWhereTheSceneCameraLooks) {
    Camera c;
    c.position = vec3(1, 2, 3);
    c.forward = vec3(1, 0, 0);
    CameraController ctl(c, 2.0f);
    ExpectNear(ctl.Get().position, vec3(1, 2, 3));
    ExpectNear(ctl.Get().forward, vec3(1, 0, 0));
}

TEST(CameraController, FlyMovesAlongTheViewAtItsSpeed) {
    CameraController ctl(Camera{}, 2.0f);  // at (0, 0, 10) looking down -z
    CameraInput in;
    in.move = vec3(0, 0, 1);
    ctl.Update(in, 0.5f);
    ExpectNear(ctl.Get().position, vec3(0, 0, 9));  // 2 units/s for 0.5 s
    in.move = vec3(1, 0, 0);
    in.fast = true;
    ctl.Update(in, 0.25f);
    ExpectNear(ctl.Get().position, vec3(2, 0, 9));  // right is +x, 4x speed
}

TEST(CameraController, LookingTurnsWithoutRollAndStopsShortOfThePoles) {
    CameraController ctl(Camera{}, 1.0f);
    CameraInput in;
    in.look = vec2(kPi / 2 / CameraController::kRadiansPerPixel, 0.0f);  // a quarter turn right
    ctl.Update(in, 0.0f);
    ExpectNear(ctl.Get().forward, vec3(1, 0, 0), 1e-4f);
    in.look = vec2(0.0f, -1e6f);  // far past straight up
    ctl.Update(in, 0.0f);
    EXPECT_NEAR(std::asin(ctl.Get().forward.y), CameraController::kMaxPitch, 1e-4f);
    EXPECT_GT(glm::length(glm::cross(ctl.Get().forward, ctl.Get().up)), 0.01f);
}

TEST(CameraController, OrbitKeepsItsDistanceToTheTarget) {
    CameraController ctl(Camera{}, 1.0f);
    ctl.SetTarget(vec3(0.0f));
    ctl.SetMode(CameraController::Mode::kOrbit);
    CameraInput in;
    in.look = vec2(300.0f, 100.0f);
    ctl.Update(in, 0.1f);
    EXPECT_NEAR(glm::length(ctl.Get().position), 10.0f, 1e-4f);
    ExpectNear(glm::normalize(-ctl.Get().position), ctl.Get().forward, 1e-5f);
    in = {};
    in.zoom = 1.0f;
    ctl.Update(in, 0.1f);
    EXPECT_NEAR(glm::length(ctl.Get().position), 9.0f, 1e-4f);
}

}  // namespace
}  // namespace rtrt
