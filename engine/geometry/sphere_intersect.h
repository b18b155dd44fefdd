#pragma once
// Ray/sphere intersection in the numerically stable form of Haines, Guenther, Akenine-Moller,
// "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems (2019), chapter 7: the
// discriminant from the closest point on the line, the roots from the non-cancelling quadratic.
//
// Production evaluates it in double on a ray brought into the sphere's space in double
// (SphereRay): in float, a ground sphere of radius 1e6 knows its own surface only to the float
// spacing of 1e6 (0.06), both in the object-space ray origin and in c = |o - c|^2 - r^2, so rays
// leaving it had to start far above it and small objects on it cast no shadow. In double the same
// errors are 2^29 times smaller. Spheres are few, so the cost is small (`rtrt bench accuracy`).
#include "engine/geometry/primitives.h"
#include "engine/geometry/ray_setup.h"

namespace rtrt {

// A ray in a sphere BLAS's object space, in double (ToObjectSpaceExact, two_level_traversal.h).
struct SphereRay {
    glm::dvec3 origin;
    glm::dvec3 dir;
};

// The float ray as it is, exactly.
RT_HD inline SphereRay MakeSphereRay(vec3 origin, vec3 dir) {
    return {glm::dvec3(origin), glm::dvec3(dir)};
}

RT_HD inline float SqrtIn(float v) { return sqrtf(v); }
RT_HD inline double SqrtIn(double v) { return sqrt(v); }
RT_HD inline float CopySignIn(float v, float sign) { return copysignf(v, sign); }
RT_HD inline double CopySignIn(double v, double sign) { return copysign(v, sign); }

// Both roots of |o + t d - c| = r in Real, t0 <= t1; false when the line misses the sphere.
template <class Real>
RT_HD inline bool SphereRoots(const Sphere& s, const glm::vec<3, Real>& o,
                              const glm::vec<3, Real>& d, Real* t0, Real* t1) {
    using V = glm::vec<3, Real>;
    const V f = o - V(s.center);
    const Real a = glm::dot(d, d);
    const Real bPrime = -glm::dot(f, d);
    const V l = f + (bPrime / a) * d;  // from the centre to the line's closest point
    const Real radius = Real(s.radius);
    const Real r2 = radius * radius;
    const Real disc = a * (r2 - glm::dot(l, l));
    if (disc < Real(0)) return false;
    const Real c = glm::dot(f, f) - r2;
    const Real q = bPrime + CopySignIn(SqrtIn(disc), bPrime);
    Real near = q != Real(0) ? c / q : Real(0);
    Real far = q / a;
    if (near > far) {
        const Real t = near;
        near = far;
        far = t;
    }
    *t0 = near;
    *t1 = far;
    return true;
}

// The nearest root in (0, tMax], as a float (compared as the float it is reported as, so that a
// hit tested again with tMax = its t is found again).
template <class Real>
RT_HD inline bool IntersectSphereIn(const Sphere& s, const glm::vec<3, Real>& o,
                                    const glm::vec<3, Real>& d, float tMax, float* tHit) {
    Real t0, t1;
    if (!SphereRoots(s, o, d, &t0, &t1)) return false;
    const float near = float(t0), far = float(t1);
    if (near > 0.0f && near <= tMax) {
        *tHit = near;
        return true;
    }
    if (far > 0.0f && far <= tMax) {
        *tHit = far;
        return true;
    }
    return false;
}

RT_HD inline bool IntersectSphere(const Sphere& s, const SphereRay& r, float tMax, float* tHit) {
    return IntersectSphereIn<double>(s, r.origin, r.dir, tMax, tHit);
}

// For a ray already in object space in float (a single BLAS, tests).
RT_HD inline bool IntersectSphere(const Sphere& s, const RaySetup& r, float tMax, float* tHit) {
    return IntersectSphere(s, MakeSphereRay(r.origin, r.dir), tMax, tHit);
}

}  // namespace rtrt
