#pragma once
// Rotation interpolation along the shorter arc.
#include <cmath>
#include <glm/gtc/quaternion.hpp>

namespace rtrt::physics {

// Normalised linear interpolation; cheaper than Slerp but not constant angular speed.
inline glm::quat Nlerp(const glm::quat& a, glm::quat b, float t) {
    if (glm::dot(a, b) < 0.0f) b = -b;  // q and -q are the same rotation: take the short way
    return glm::normalize(a * (1.0f - t) + b * t);
}

// Shoemake 1985, "Animating Rotation with Quaternion Curves": constant angular speed along the
// shorter great arc. Nearly parallel inputs fall back to Nlerp, where sin(theta) loses precision.
inline glm::quat Slerp(const glm::quat& a, glm::quat b, float t) {
    float cosTheta = glm::dot(a, b);
    if (cosTheta < 0.0f) {
        b = -b;
        cosTheta = -cosTheta;
    }
    if (cosTheta > 0.9995f) return Nlerp(a, b, t);
    const float theta = std::acos(cosTheta);
    const float sinTheta = std::sin(theta);
    const float wa = std::sin((1.0f - t) * theta) / sinTheta;
    const float wb = std::sin(t * theta) / sinTheta;
    return glm::normalize(a * wa + b * wb);
}

}  // namespace rtrt::physics
