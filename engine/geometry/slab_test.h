#pragma once
// Ray/box test that is inclusive (rays in a box face hit it) and NaN-safe: near and far planes
// are chosen by the sign of the direction, so a 0 * inf = NaN lane is dropped by MaxOrKeep
// instead of poisoning the interval. The far distance is widened by 1 + 2 gamma(3) as in
// pbrt-v4 ("Bounds3::IntersectP") so rounding never culls a box the ray touches.
#include "engine/geometry/ray_setup.h"

namespace rtrt {

// The test on a box given by its corners. The sign of 1/d picks the near and far planes
// (1/-0 = -inf counts as negative).
RT_HD inline bool SlabTest(vec3 lo, vec3 hi, const RaySetup& r, float tMax, float* tEntry) {
    const bool nx = r.invDir.x < 0.0f, ny = r.invDir.y < 0.0f, nz = r.invDir.z < 0.0f;
    const float tx0 = ((nx ? hi.x : lo.x) - r.origin.x) * r.invDir.x;
    const float tx1 = ((nx ? lo.x : hi.x) - r.origin.x) * r.invDir.x;
    const float ty0 = ((ny ? hi.y : lo.y) - r.origin.y) * r.invDir.y;
    const float ty1 = ((ny ? lo.y : hi.y) - r.origin.y) * r.invDir.y;
    const float tz0 = ((nz ? hi.z : lo.z) - r.origin.z) * r.invDir.z;
    const float tz1 = ((nz ? lo.z : hi.z) - r.origin.z) * r.invDir.z;
    // The accumulators start from 0 and tMax, never NaN, so NaN lanes are dropped.
    const float t0 = MaxOrKeep(tz0, MaxOrKeep(ty0, MaxOrKeep(tx0, 0.0f)));
    const float t1 = MinOrKeep(tz1, MinOrKeep(ty1, MinOrKeep(tx1, tMax)));
    *tEntry = t0;
    return t0 <= t1 * (1.0f + 2.0f * Gamma(3));
}

}  // namespace rtrt
