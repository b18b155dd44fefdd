#pragma once
// Collision shapes, in the body's frame and in world units (LocalTransform::scale is ignored).
#include <cmath>
#include <cstdint>

#include "engine/core/math.h"

namespace rtrt::physics {

enum class ColliderShape : uint8_t { kSphere, kBox, kPlane };

// A sphere about the body's origin; a box about its origin, oriented by its rotation; or an
// infinite plane (a half-space: everything behind it is solid) through its origin with the given
// normal in the body's frame. Planes are always static, whatever the body's mass.
struct Collider {
    ColliderShape shape = ColliderShape::kSphere;
    float radius = 0.5f;
    vec3 halfExtents{0.5f};
    vec3 normal{0.0f, 1.0f, 0.0f};

    static Collider Sphere(float radius) {
        return {ColliderShape::kSphere, radius, vec3(0.0f), {}};
    }
    static Collider Box(vec3 halfExtents) { return {ColliderShape::kBox, 0.0f, halfExtents, {}}; }
    static Collider Plane(vec3 normal) {
        return {ColliderShape::kPlane, 0.0f, vec3(0.0f), glm::normalize(normal)};
    }
};

// Principal moments of inertia of a solid of uniform density about its centre (zero for a plane).
inline vec3 InertiaDiagonal(const Collider& collider, float mass) {
    switch (collider.shape) {
        case ColliderShape::kSphere:
            return vec3(0.4f * mass * collider.radius * collider.radius);
        case ColliderShape::kBox: {
            const vec3 h2 = collider.halfExtents * collider.halfExtents;
            return (mass / 3.0f) * vec3(h2.y + h2.z, h2.x + h2.z, h2.x + h2.y);
        }
        case ColliderShape::kPlane:
            break;
    }
    return vec3(0.0f);
}

// Radius of a sphere about the body's origin that holds the shape (0 for a plane).
inline float BoundingRadius(const Collider& collider) {
    switch (collider.shape) {
        case ColliderShape::kSphere:
            return collider.radius;
        case ColliderShape::kBox:
            return glm::length(collider.halfExtents);
        case ColliderShape::kPlane:
            break;
    }
    return 0.0f;
}

// Half the extent of the shape on each world axis once turned by ROTATION: the half size of the
// box that holds it about the body's origin (a plane's is 0; it is kept out of such boxes).
inline vec3 WorldHalfExtent(const Collider& collider, const glm::mat3& rotation) {
    if (collider.shape != ColliderShape::kBox) return vec3(collider.radius);
    const vec3 h = collider.halfExtents;
    vec3 extent;
    for (int k = 0; k < 3; ++k)
        extent[k] = std::fabs(rotation[0][k]) * h.x + std::fabs(rotation[1][k]) * h.y +
                    std::fabs(rotation[2][k]) * h.z;
    return extent;
}

}  // namespace rtrt::physics
