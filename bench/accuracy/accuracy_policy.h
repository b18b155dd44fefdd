#pragma once
// The accuracy variants: the less robust textbook forms the benchmark (`rtrt bench accuracy`)
// compares against the defaults, as trace policies (engine/render_rt/trace_policy.h). Each bit
// swaps one step of the trace, inside the policy function of that step; AccuracyPolicy<0> traces
// as TracePolicy. Only the benchmark's own translation units instantiate them.
#include "bench/accuracy/moller_trumbore.h"
#include "bench/accuracy/sphere_intersect_naive.h"
#include "engine/render_rt/trace_policy.h"

namespace rtrt {

enum AccuracyVariant : uint32_t {
    kAccuracyDefault = 0,
    kAccuracyMollerTrumbore = 1u << 0,  // triangles: Moller-Trumbore instead of watertight
    kAccuracyNaiveSphere = 1u << 1,     // spheres: textbook quadratic instead of RTG ch. 7
    kAccuracyFixedEpsilon = 1u << 2,    // ray origins: p + 1e-4 n instead of error bounds
    // Float only: triangle hits within their error bound of t = 0 rejected, not decided in
    // double; spheres in float (the forms before docs/robustness.md's "near hits in double").
    kAccuracyFloatOnly = 1u << 3,
};
inline constexpr uint32_t kAllAccuracyBits = 15;
// The combinations the benchmark and its tests use, each one instantiation of the trace
// (accuracy_dispatch.h); the "textbook" setting is the first three bits together.
inline constexpr uint32_t kTextbookAccuracy =
    kAccuracyMollerTrumbore | kAccuracyNaiveSphere | kAccuracyFixedEpsilon;
inline constexpr uint32_t kUsedAccuracyVariants[] = {
    kAccuracyDefault,
    kAccuracyMollerTrumbore,
    kAccuracyNaiveSphere,
    kAccuracyFixedEpsilon,
    kAccuracyMollerTrumbore | kAccuracyFixedEpsilon,
    kTextbookAccuracy,
    kAccuracyFloatOnly};

// kAccuracyFixedEpsilon's offset: the common shortcut, too little far from the origin (acne) and
// too much beside thin or small geometry (leaks).
inline constexpr float kFixedRayEpsilon = 1e-4f;

template <uint32_t kVariant>
struct AccuracyPolicy {
    static RT_HD bool IntersectTriangle(const Triangle& tri, const RaySetup& r, float tMax,
                                        TriangleHit* hit) {
        if constexpr ((kVariant & kAccuracyMollerTrumbore) != 0)
            return IntersectTriangleMollerTrumbore(tri, r, tMax, hit);
        else if constexpr ((kVariant & kAccuracyFloatOnly) != 0)
            return rtrt::IntersectTriangle<false>(tri, r, tMax, hit);
        else
            return TracePolicy::IntersectTriangle(tri, r, tMax, hit);
    }

    static RT_HD bool IntersectSphere(const Sphere& s, const SphereRay& r, float tMax,
                                      float* tHit) {
        if constexpr ((kVariant & kAccuracyNaiveSphere) != 0)
            return IntersectSphereNaive(s, r, tMax, tHit);
        else if constexpr ((kVariant & kAccuracyFloatOnly) != 0)
            return IntersectSphereIn<float>(s, vec3(r.origin), r.dir, tMax, tHit);
        else
            return TracePolicy::IntersectSphere(s, r, tMax, tHit);
    }

    static RT_HD Ray SpawnRay(const Surface& s, vec3 dir, float tMax = kInfinity) {
        Ray r = TracePolicy::SpawnRay(s, dir, tMax);
        if constexpr ((kVariant & kAccuracyFixedEpsilon) != 0) {
            const float side = glm::dot(dir, s.geomNormal) < 0.0f ? -1.0f : 1.0f;
            r.origin = s.point + (side * kFixedRayEpsilon) * s.geomNormal;
        }
        return r;
    }
};

}  // namespace rtrt
