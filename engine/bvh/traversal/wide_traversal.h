#pragma once
// Traversal of the 4-wide BVH (bvh4.h) in portable code, the GPU's form of bvh4_traversal.h's
// SSE loop: the four children's slab tests of a node, the hit ones sorted far to near by their
// entry distance, the nearest visited next and the rest stacked with their distance, so that
// entries already beyond the closest hit are dropped when popped. A node is eight 16-byte loads
// instead of a binary tree's two per child pair, and a ray visits about a third as many nodes.
//
// The sort is a fixed network of selects (an indexed local array would live in slow local memory
// on the GPU); missed children sort as +inf and are never stacked. A leaf child is stacked as a
// reference to its parent's slot (kWideLeaf | node << 2 | slot) and read back when popped, so
// that one 32-bit word names any entry. Same slab semantics as slab_test.h; leaves use the same
// primitive tests.
#include "engine/bvh/layout/bvh4.h"
#include "engine/bvh/traversal/traversal.h"
#include "engine/core/math.h"
#include "engine/geometry/ray_setup.h"

namespace rtrt {

inline constexpr uint32_t kWideLeaf = 0x80000000u;
inline constexpr uint32_t kWideStackSize = 3 * kBvhStackSize + 4;

struct WideLanes {
    float x, y, z, w;
};
struct WideIndices {
    uint32_t x, y, z, w;
};
// A node's planes, loaded once: on the GPU as eight read-only 16-byte loads.
struct WideNodePlanes {
    WideLanes minX, minY, minZ, maxX, maxY, maxZ;
    WideIndices child, count;
};

RT_HD inline WideNodePlanes LoadWideNode(const Bvh4Node& node) {
#if defined(__CUDA_ARCH__)
    const float4* p = reinterpret_cast<const float4*>(&node);
    const uint4* q = reinterpret_cast<const uint4*>(&node);
    auto f = [](float4 v) { return WideLanes{v.x, v.y, v.z, v.w}; };
    auto u = [](uint4 v) { return WideIndices{v.x, v.y, v.z, v.w}; };
    return {f(__ldg(p + 0)), f(__ldg(p + 1)), f(__ldg(p + 2)), f(__ldg(p + 3)),
            f(__ldg(p + 4)), f(__ldg(p + 5)), u(__ldg(q + 6)), u(__ldg(q + 7))};
#else
    auto f = [](const float* v) { return WideLanes{v[0], v[1], v[2], v[3]}; };
    auto u = [](const uint32_t* v) { return WideIndices{v[0], v[1], v[2], v[3]}; };
    return {f(node.minX), f(node.minY), f(node.minZ),  f(node.maxX),
            f(node.maxY), f(node.maxZ), u(node.child), u(node.count)};
#endif
}

// Entry distance of the ray into one child's box, or +inf when it misses (as SlabTest).
RT_HD inline float WideChildEntry(float lx, float ly, float lz, float hx, float hy, float hz,
                                  const RaySetup& r, float tMax) {
    const bool nx = r.invDir.x < 0.0f, ny = r.invDir.y < 0.0f, nz = r.invDir.z < 0.0f;
    const float tx0 = ((nx ? hx : lx) - r.origin.x) * r.invDir.x;
    const float tx1 = ((nx ? lx : hx) - r.origin.x) * r.invDir.x;
    const float ty0 = ((ny ? hy : ly) - r.origin.y) * r.invDir.y;
    const float ty1 = ((ny ? ly : hy) - r.origin.y) * r.invDir.y;
    const float tz0 = ((nz ? hz : lz) - r.origin.z) * r.invDir.z;
    const float tz1 = ((nz ? lz : hz) - r.origin.z) * r.invDir.z;
    const float t0 = MaxOrKeep(tz0, MaxOrKeep(ty0, MaxOrKeep(tx0, 0.0f)));
    const float t1 = MinOrKeep(tz1, MinOrKeep(ty1, MinOrKeep(tx1, tMax)));
    return t0 <= t1 * (1.0f + 2.0f * Gamma(3)) ? t0 : kInfinity;
}

// Orders two (distance, entry) pairs far first.
RT_HD inline void FarFirst(float& ta, uint32_t& ea, float& tb, uint32_t& eb) {
    const bool swap = ta < tb;
    const float t = swap ? tb : ta;
    const uint32_t e = swap ? eb : ea;
    tb = swap ? ta : tb;
    eb = swap ? ea : eb;
    ta = t;
    ea = e;
}

// Both queries, as Traverse4: test(slot, tMax) tests one primitive; kOccluded stops at the first
// that blocks the ray, with tMax fixed, and prunes no pops.
template <Query kQuery, typename TestPrim>
RT_HD inline bool TraverseWide(const Bvh4Node* nodes, const RaySetup& ray, float& tMax,
                               TestPrim&& test) {
    uint32_t stackEntry[kWideStackSize];
    float stackT[kWideStackSize];
    uint32_t stackSize = 0;
    bool found = false;
    uint32_t current = 0;
    for (;;) {
        if ((current & kWideLeaf) != 0) {
            const uint32_t node = (current & ~kWideLeaf) >> 2, slot = current & 3u;
            const uint32_t first = nodes[node].child[slot], count = nodes[node].count[slot];
            for (uint32_t i = 0; i < count; ++i) {
                if (test(first + i, tMax)) {
                    if constexpr (kQuery == Query::kOccluded) return true;
                    found = true;
                }
            }
        } else {
            const WideNodePlanes n = LoadWideNode(nodes[current]);
            const uint32_t leafBase = kWideLeaf | current << 2;
            float t0 = WideChildEntry(n.minX.x, n.minY.x, n.minZ.x, n.maxX.x, n.maxY.x, n.maxZ.x,
                                      ray, tMax);
            float t1 = WideChildEntry(n.minX.y, n.minY.y, n.minZ.y, n.maxX.y, n.maxY.y, n.maxZ.y,
                                      ray, tMax);
            float t2 = WideChildEntry(n.minX.z, n.minY.z, n.minZ.z, n.maxX.z, n.maxY.z, n.maxZ.z,
                                      ray, tMax);
            float t3 = WideChildEntry(n.minX.w, n.minY.w, n.minZ.w, n.maxX.w, n.maxY.w, n.maxZ.w,
                                      ray, tMax);
            uint32_t e0 = n.count.x ? leafBase | 0u : n.child.x;
            uint32_t e1 = n.count.y ? leafBase | 1u : n.child.y;
            uint32_t e2 = n.count.z ? leafBase | 2u : n.child.z;
            uint32_t e3 = n.count.w ? leafBase | 3u : n.child.w;
            // Far to near (misses, +inf, first): a five-exchange sorting network.
            FarFirst(t0, e0, t1, e1);
            FarFirst(t2, e2, t3, e3);
            FarFirst(t0, e0, t2, e2);
            FarFirst(t1, e1, t3, e3);
            FarFirst(t1, e1, t2, e2);
            if (t3 != kInfinity) {
                if (t0 != kInfinity) {
                    stackEntry[stackSize] = e0;
                    stackT[stackSize++] = t0;
                }
                if (t1 != kInfinity) {
                    stackEntry[stackSize] = e1;
                    stackT[stackSize++] = t1;
                }
                if (t2 != kInfinity) {
                    stackEntry[stackSize] = e2;
                    stackT[stackSize++] = t2;
                }
                current = e3;
                continue;
            }
        }
        // Pop, skipping entries the closest hit so far already lies before (widened like the
        // slab test, see bvh4_traversal.h).
        for (;;) {
            if (stackSize == 0) return found;
            --stackSize;
            current = stackEntry[stackSize];
            if (kQuery == Query::kOccluded || stackT[stackSize] <= tMax * (1.0f + 2.0f * Gamma(3)))
                break;
        }
    }
}

}  // namespace rtrt
