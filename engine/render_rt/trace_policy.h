#pragma once
// The steps of the trace that a study may replace, as one policy type that the trace functions
// take as a template parameter (trace.h, pixel_kernel.h): the primitive tests, static
// IntersectTriangle and IntersectSphere as in PrimitiveTests, and static SpawnRay, how secondary
// rays leave a surface, as in surface.h. TracePolicy is production's: watertight triangles, the
// RTG ch. 7 sphere test and origins offset by their error bounds. The accuracy study's variants
// are policies of their own (bench/accuracy/accuracy_policy.h).
#include "engine/geometry/primitive_tests.h"
#include "engine/render_rt/surface.h"

namespace rtrt {

struct TracePolicy : PrimitiveTests {
    static RT_HD Ray SpawnRay(const Surface& s, vec3 dir, float tMax = kInfinity) {
        return rtrt::SpawnRay(s, dir, tMax);
    }
};

}  // namespace rtrt
