#pragma once
// The slab test of engine/geometry on a node of a BVH in global memory.
#include "engine/bvh/layout/bvh_node.h"
#include "engine/geometry/slab_test.h"

namespace rtrt {

// What a traversal needs of a node to step into it: the words the slab test's loads bring along
// with the box. Kept from the test of a child (and on the stack for the children that wait), it
// spares the step into that child a dependent load of its own (on the GPU a round trip to L1 or
// L2 on every step down the tree).
struct NodeHeader {
    uint32_t leftFirst;
    uint32_t primCount;
    RT_HD bool IsLeaf() const { return primCount > 0; }
};

// The test on a node of a BVH in global memory; header receives the node's header. Forced inline
// on the host, where g++ called it once per ray.
RT_HOST_ALWAYS_INLINE RT_HD inline bool SlabTest(const BvhNode& node, const RaySetup& r, float tMax,
                                                 float* tEntry, NodeHeader* header) {
#if defined(__CUDA_ARCH__)
    // Two 16-byte read-only loads, then selects: six dynamically indexed loads would cost six
    // load instructions per box on the GPU, and deriving the planes from the sign of 1/d rather
    // than the setup's plane offsets leaves those dead, which saves registers in the loops.
    // Nodes are read-only while a kernel traces.
    const float4 lo = __ldg(reinterpret_cast<const float4*>(&node));
    const float4 hi = __ldg(reinterpret_cast<const float4*>(&node) + 1);
    *header = {__float_as_uint(lo.w), __float_as_uint(hi.w)};
    return SlabTest(vec3(lo.x, lo.y, lo.z), vec3(hi.x, hi.y, hi.z), r, tMax, tEntry);
#else
    *header = {node.leftFirst, node.primCount};
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

// The test alone.
RT_HOST_ALWAYS_INLINE RT_HD inline bool SlabTest(const BvhNode& node, const RaySetup& r, float tMax,
                                                 float* tEntry) {
    NodeHeader unused;
    return SlabTest(node, r, tMax, tEntry, &unused);
}

}  // namespace rtrt
