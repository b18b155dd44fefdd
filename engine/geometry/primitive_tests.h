#pragma once
// The primitive tests of the traversals, as a type: the traversals take it as a template parameter
// (`class Tests`) so that a study can swap a test without a parameter in any production signature
// (the trace's policy, engine/render_rt/trace_policy.h). These are production's: the watertight
// triangle test and the stable sphere test.
#include "engine/geometry/sphere_intersect.h"
#include "engine/geometry/triangle_intersect.h"

namespace rtrt {

struct PrimitiveTests {
    // Forced inline as the test itself (triangle_intersect.h): else the CPU's leaf loops call
    // this wrapper.
    RT_HOST_ALWAYS_INLINE static RT_HD bool IntersectTriangle(const Triangle& tri,
                                                              const RaySetup& r, float tMax,
                                                              TriangleHit* hit) {
        return rtrt::IntersectTriangle(tri, r, tMax, hit);
    }
    static RT_HD bool IntersectSphere(const Sphere& s, const SphereRay& r, float tMax,
                                      float* tHit) {
        return rtrt::IntersectSphere(s, r, tMax, tHit);
    }
};

}  // namespace rtrt
