#pragma once
// Ray/sphere intersection in the numerically stable form of Haines, Guenther, Akenine-Moller,
// "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems (2019), chapter 7: the
// discriminant from the closest point on the line, the roots from the non-cancelling quadratic.
//
// Production takes the two quantities that cancel in double: the ray origin relative to the
// centre, f = o - c, from an origin brought into the sphere's space in double (SphereRay), and
// c = |f|^2 - r^2, which sets the near root. In float, a ground sphere of radius 1e6 knows both
// only to the float spacing of 1e6 (0.06), so a ray leaving it could not tell whether it started
// inside, rays had to start far above it and small objects on it cast no shadow. The rest (b, the
// discriminant, q) is relative-error safe in float. `rtrt bench accuracy` shows the cost.
#include "engine/geometry/primitives.h"
#include "engine/geometry/ray_setup.h"

namespace rtrt {

// A ray in a sphere BLAS's object space, its origin in double (ToObjectSpaceExact,
// two_level_traversal.h).
struct SphereRay {
    glm::dvec3 origin;
    vec3 dir;
};

// The float ray as it is, exactly.
RT_HD inline SphereRay MakeSphereRay(vec3 origin, vec3 dir) { return {glm::dvec3(origin), dir}; }

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
    const glm::dvec3 fDouble = r.origin - glm::dvec3(s.center);
    const double radius = s.radius;
    const double c = glm::dot(fDouble, fDouble) - radius * radius;
    const vec3 f(fDouble);
    const float a = glm::dot(r.dir, r.dir);
    const float bPrime = -glm::dot(f, r.dir);
    const vec3 l = f + (bPrime / a) * r.dir;  // from the centre to the line's closest point
    const float disc = a * (s.radius * s.radius - glm::dot(l, l));
    if (disc < 0.0f) return false;
    const float q = bPrime + copysignf(sqrtf(disc), bPrime);
    // c is exact to its rounding to float here, so the near root is too (no double division).
    float t0 = q != 0.0f ? float(c) / q : 0.0f;
    float t1 = q / a;
    if (t0 > t1) {
        const float t = t0;
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

// For a ray already in object space in float (a single BLAS, tests).
RT_HD inline bool IntersectSphere(const Sphere& s, const RaySetup& r, float tMax, float* tHit) {
    return IntersectSphere(s, MakeSphereRay(r.origin, r.dir), tMax, tHit);
}

}  // namespace rtrt
