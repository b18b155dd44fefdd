#pragma once
// Ray/box test that is inclusive (rays in a box face hit it) and NaN-safe: near and far planes
// are chosen by the sign of the direction, so a 0 * inf = NaN lane is dropped by MaxOrKeep
// instead of poisoning the interval. The far distance is widened by 1 + 2 gamma(3) as in
// pbrt-v4 ("Bounds3::IntersectP") so rounding never culls a box the ray touches.
#include "engine/bvh/bvh_node.h"
#include "engine/bvh/ray_setup.h"

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

// The test on a node of a BVH in global memory.
RT_HD inline bool SlabTest(const BvhNode& node, const RaySetup& r, float tMax, float* tEntry) {
#if defined(__CUDA_ARCH__)
    // Two 16-byte read-only loads, then selects: six dynamically indexed loads would cost six
    // load instructions per box on the GPU, and deriving the planes from the sign of 1/d rather
    // than the setup's plane offsets leaves those dead, which saves registers in the loops.
    // Nodes are read-only while a kernel traces.
    const float4 lo = __ldg(reinterpret_cast<const float4*>(&node));
    const float4 hi = __ldg(reinterpret_cast<const float4*>(&node) + 1);
    return SlabTest(vec3(lo.x, lo.y, lo.z), vec3(hi.x, hi.y, hi.z), r, tMax, tEntry);
#else
    // Reads the near and far planes straight from the node (no copy of its bounds).
    const float* b = &node.boundsMin.x;
    const float tx0 = (b[r.nearOffset[0]] - r.origin.x) * r.invDir.x;
    const float tx1 = (b[r.farOffset[0]] - r.origin.x) * r.invDir.x;
    const float ty0 = (b[r.nearOffset[1]] - r.origin.y) * r.invDir.y;
    const float ty1 = (b[r.farOffset[1]] - r.origin.y) * r.invDir.y;
    const float tz0 = (b[r.nearOffset[2]] - r.origin.z) * r.invDir.z;
    const float tz1 = (b[r.farOffset[2]] - r.origin.z) * r.invDir.z;
    const float t0 = MaxOrKeep(tz0, MaxOrKeep(ty0, MaxOrKeep(tx0, 0.0f)));
    const float t1 = MinOrKeep(tz1, MinOrKeep(ty1, MinOrKeep(tx1, tMax)));
    *tEntry = t0;
    return t0 <= t1 * (1.0f + 2.0f * Gamma(3));
#endif
}

}  // namespace rtrt
