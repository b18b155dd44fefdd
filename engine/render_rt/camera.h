#pragma once
// The camera of the original paper: a position, a forward and an up direction and a vertical
// field of view; the image plane sits one unit ahead, its height 2 tan(fovY / 2).
#include "engine/core/ray.h"

namespace rtrt {

struct Camera {
    vec3 position{0, 0, 10};
    vec3 forward{0, 0, -1};
    vec3 up{0, 1, 0};
    float fovYDegrees = 45.0f;
};

// Whether FORWARD and UP span the camera's basis: both finite and non-zero, and UP not parallel
// to FORWARD (the sine of their angle at least 1e-6), so that MakeCameraFrame's cross product
// has a direction.
inline bool CameraBasisDefined(vec3 forward, vec3 up) {
    if (!IsFinite(forward) || !IsFinite(up)) return false;
    if (forward == vec3(0.0f) || up == vec3(0.0f)) return false;
    const vec3 f = glm::normalize(ScaledForNormalize(forward));
    const vec3 u = glm::normalize(ScaledForNormalize(up));
    return glm::length(glm::cross(f, u)) >= 1e-6f;
}

// Orthonormal basis and image-plane scale, computed once per frame.
struct CameraFrame {
    vec3 origin;
    vec3 forward, right, up;
    float tanHalfFovY;
    float aspect;
};

inline CameraFrame MakeCameraFrame(const Camera& camera, uint32_t width, uint32_t height) {
    CameraFrame f;
    f.origin = camera.position;
    f.forward = glm::normalize(camera.forward);
    f.right = glm::normalize(glm::cross(f.forward, camera.up));
    f.up = glm::cross(f.right, f.forward);
    f.tanHalfFovY = tanf(0.5f * camera.fovYDegrees * kPi / 180.0f);
    f.aspect = float(width) / float(height);
    return f;
}

// The primary ray through image position (px, py) in pixels; (0, 0) is the top left corner.
RT_HD inline Ray PrimaryRay(const CameraFrame& f, float px, float py, uint32_t width,
                            uint32_t height) {
    const float sx = (2.0f * px / float(width) - 1.0f) * f.tanHalfFovY * f.aspect;
    const float sy = (1.0f - 2.0f * py / float(height)) * f.tanHalfFovY;
    Ray ray;
    ray.origin = f.origin;
    ray.dir = glm::normalize(f.forward + sx * f.right + sy * f.up);
    ray.tMax = kInfinity;
    ray.pad = 0.0f;
    return ray;
}

// The primary ray through the centre of pixel (x, y); y = 0 is the top row.
RT_HD inline Ray PrimaryRay(const CameraFrame& f, uint32_t x, uint32_t y, uint32_t width,
                            uint32_t height) {
    return PrimaryRay(f, float(x) + 0.5f, float(y) + 0.5f, width, height);
}

}  // namespace rtrt
