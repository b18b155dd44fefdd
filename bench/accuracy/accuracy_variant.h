#pragma once
// Compile-time accuracy variants: the less robust textbook forms the benchmark
// (`rtrt bench accuracy`) compares against the defaults. Each bit swaps one step of the trace; 0
// is the default trace, so kernels that are not the benchmark's compile exactly as before. Only
// the benchmark's own translation units instantiate other values.
#include "bench/accuracy/moller_trumbore.h"
#include "bench/accuracy/sphere_intersect_naive.h"
#include "engine/geometry/sphere_intersect.h"
#include "engine/geometry/triangle_intersect.h"

namespace rtrt {

enum AccuracyVariant : uint32_t {
    kAccuracyDefault = 0,
    kAccuracyMollerTrumbore = 1u << 0,  // triangles: Moller-Trumbore instead of watertight
    kAccuracyNaiveSphere = 1u << 1,     // spheres: textbook quadratic instead of RTG ch. 7
    kAccuracyFixedEpsilon = 1u << 2,    // ray origins: p + 1e-4 n instead of error bounds
};
inline constexpr uint32_t kAllAccuracyBits = 7;

template <uint32_t kAccuracy>
RT_HD inline bool IntersectTriangleAs(const Triangle& tri, const RaySetup& r, float tMax,
                                      TriangleHit* hit) {
    if constexpr ((kAccuracy & kAccuracyMollerTrumbore) != 0)
        return IntersectTriangleMollerTrumbore(tri, r, tMax, hit);
    else
        return IntersectTriangle(tri, r, tMax, hit);
}

template <uint32_t kAccuracy>
RT_HD inline bool IntersectSphereAs(const Sphere& s, const RaySetup& r, float tMax, float* tHit) {
    if constexpr ((kAccuracy & kAccuracyNaiveSphere) != 0)
        return IntersectSphereNaive(s, r, tMax, tHit);
    else
        return IntersectSphere(s, r, tMax, tHit);
}

}  // namespace rtrt
