#pragma once
// The textbook ray/sphere test, kept as the accuracy benchmark's foil to the Ray Tracing Gems
// ch. 7 form (sphere_intersect.h): the discriminant b^2 - a c subtracts two numbers of size
// |o - c|^2 |d|^2, so for a sphere small against its distance it loses every digit of r^2 and
// the silhouette frays (Haines et al. 2019, figure 7-1).
#include "engine/geometry/primitives.h"
#include "engine/geometry/sphere_intersect.h"

namespace rtrt {

// In float, as the textbook has it (the object-space ray rounded to float).
RT_HD inline bool IntersectSphereNaive(const Sphere& s, const SphereRay& r, float tMax,
                                       float* tHit) {
    const vec3 dir(r.dir);
    const vec3 f = vec3(r.origin) - s.center;
    const float a = glm::dot(dir, dir);
    const float b = glm::dot(f, dir);
    const float c = glm::dot(f, f) - s.radius * s.radius;
    const float disc = b * b - a * c;
    if (disc < 0.0f) return false;
    const float root = sqrtf(disc);
    const float t0 = (-b - root) / a;
    const float t1 = (-b + root) / a;
    if (t0 > 0.0f && t0 <= tMax) {
        *tHit = t0;
        return true;
    }
    if (t1 > 0.0f && t1 <= tMax) {
        *tHit = t1;
        return true;
    }
    return false;
}

}  // namespace rtrt
