#pragma once
// Motions given by a formula of time, applied on top of a pose.
#include <memory>
#include <variant>

#include "engine/physics_anim/orthonormal_basis.h"
#include "engine/physics_anim/path.h"
#include "engine/physics_anim/transform.h"

namespace rtrt::physics {

// Turns about axis at angularSpeed radians per second (counter-clockwise looking down the axis):
// rotation = angleAxis(angularSpeed * t, axis) * rotation.
struct Spin {
    vec3 axis{0.0f, 1.0f, 0.0f};
    float angularSpeed = 1.0f;
};

// Circles centre once per period seconds in the plane normal to axis, counter-clockwise looking
// down the axis: translation = centre + angleAxis(2 pi t / period, axis) * (radius * u), where u is
// the first vector of the orthonormal basis OrthonormalBasis(axis) builds (+X for a +Y axis).
struct Orbit {
    vec3 centre{0.0f};
    float radius = 1.0f;
    vec3 axis{0.0f, 1.0f, 0.0f};
    float period = 1.0f;
};

// Adds amplitude * sin(2 pi frequency t) along axis to the translation.
struct Bob {
    float amplitude = 0.1f;
    float frequency = 1.0f;  // Hz
    vec3 axis{0.0f, 1.0f, 0.0f};
};

// Moves along path at speed units per second, from its first point at t = 0: translation =
// path->PointAt(speed * t). A closed path loops; an open one stops at its end.
struct FollowPath {
    std::shared_ptr<const Path> path;
    float speed = 1.0f;
};

using ProceduralMotion = std::variant<Spin, Orbit, Bob, FollowPath>;

// Applies motion at time t (seconds) to pose.
void ApplyMotion(const ProceduralMotion& motion, double t, LocalTransform& pose);

}  // namespace rtrt::physics
