#pragma once
// Ray/box test that is inclusive (rays in a box face hit it) and NaN-safe: near and far planes
// are chosen by the sign of the direction, so a 0 * inf = NaN lane is dropped by MaxOrKeep
// instead of poisoning the interval. The far distance is widened by 1 + 2 gamma(3) as in
// pbrt-v4 ("Bounds3::IntersectP") so rounding never culls a box the ray touches.
#include "engine/bvh/bvh_node.h"
#include "engine/bvh/ray_setup.h"

namespace rtrt {

RT_HD inline bool SlabTest(vec3 boxMin, vec3 boxMax, const RaySetup& r, float tMax, float* tEntry) {
    const vec3 lo[2] = {boxMin, boxMax};
    const float tx0 = (lo[r.negative[0]].x - r.origin.x) * r.invDir.x;
    const float tx1 = (lo[1 - r.negative[0]].x - r.origin.x) * r.invDir.x;
    const float ty0 = (lo[r.negative[1]].y - r.origin.y) * r.invDir.y;
    const float ty1 = (lo[1 - r.negative[1]].y - r.origin.y) * r.invDir.y;
    const float tz0 = (lo[r.negative[2]].z - r.origin.z) * r.invDir.z;
    const float tz1 = (lo[1 - r.negative[2]].z - r.origin.z) * r.invDir.z;
    // The accumulators start from 0 and tMax, never NaN, so NaN lanes are dropped.
    const float t0 = MaxOrKeep(tz0, MaxOrKeep(ty0, MaxOrKeep(tx0, 0.0f)));
    const float t1 = MinOrKeep(tz1, MinOrKeep(ty1, MinOrKeep(tx1, tMax)));
    *tEntry = t0;
    return t0 <= t1 * (1.0f + 2.0f * Gamma(3));
}

RT_HD inline bool SlabTest(const BvhNode& node, const RaySetup& r, float tMax, float* tEntry) {
    return SlabTest(node.boundsMin, node.boundsMax, r, tMax, tEntry);
}

}  // namespace rtrt
