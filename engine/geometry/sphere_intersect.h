#pragma once
// Ray/sphere intersection in the numerically stable form of Haines, Guenther, Akenine-Moller,
// "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems (2019), chapter 7: the
// discriminant from the closest point on the line, the roots from the non-cancelling quadratic.
#include "engine/geometry/primitives.h"
#include "engine/geometry/ray_setup.h"

namespace rtrt {

RT_HD inline bool IntersectSphere(const Sphere& s, const RaySetup& r, float tMax, float* tHit) {
    const vec3 f = r.origin - s.center;
    const float a = glm::dot(r.dir, r.dir);
    const float bPrime = -glm::dot(f, r.dir);
    const vec3 l = f + (bPrime / a) * r.dir;  // from the centre to the line's closest point
    const float r2 = s.radius * s.radius;
    const float disc = a * (r2 - glm::dot(l, l));
    if (disc < 0.0f) return false;
    const float c = glm::dot(f, f) - r2;
    const float q = bPrime + copysignf(sqrtf(disc), bPrime);
    float t0 = q != 0.0f ? c / q : 0.0f;
    float t1 = q / a;
    if (t0 > t1) {
        float t = t0;
        t0 = t1;
        t1 = t;
    }
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
