#include "engine/physics_anim/procedural_motion.h"

#include <cmath>

namespace rtrt::physics {

namespace {

constexpr double kTwoPi = 6.283185307179586476925;

// Angles in double and reduced to one turn before the float conversion, so a motion stays as
// smooth after an hour as at start.
float Angle(double radians) { return static_cast<float>(std::fmod(radians, kTwoPi)); }

vec3 UnitOr(vec3 v, vec3 fallback) {
    const float length = glm::length(v);
    return length > 0.0f ? v / length : fallback;
}

}  // namespace

void ApplyMotion(const ProceduralMotion& motion, double t, LocalTransform& pose) {
    const vec3 kUp(0.0f, 1.0f, 0.0f);
    if (const auto* spin = std::get_if<Spin>(&motion)) {
        const vec3 axis = UnitOr(spin->axis, kUp);
        pose.rotation = glm::angleAxis(Angle(spin->angularSpeed * t), axis) * pose.rotation;
    } else if (const auto* orbit = std::get_if<Orbit>(&motion)) {
        const vec3 axis = UnitOr(orbit->axis, kUp);
        vec3 u;
        vec3 v;
        OrthonormalBasis(axis, u, v);
        const double turns = orbit->period > 0.0f ? t / orbit->period : 0.0;
        const float angle = Angle(kTwoPi * (turns - std::floor(turns)));
        pose.translation =
            orbit->centre + orbit->radius * (std::cos(angle) * u + std::sin(angle) * v);
    } else if (const auto* bob = std::get_if<Bob>(&motion)) {
        const double cycles = bob->frequency * t;
        const float angle = Angle(kTwoPi * (cycles - std::floor(cycles)));
        pose.translation += UnitOr(bob->axis, kUp) * (bob->amplitude * std::sin(angle));
    } else if (const auto* follow = std::get_if<FollowPath>(&motion)) {
        if (!follow->path) return;
        double distance = follow->speed * t;
        const double length = follow->path->Length();
        if (follow->path->Closed() && length > 0.0) {  // wrap in double, as for the angles
            distance = std::fmod(distance, length);
            if (distance < 0.0) distance += length;
        }
        pose.translation = follow->path->PointAt(static_cast<float>(distance));
    }
}

}  // namespace rtrt::physics
