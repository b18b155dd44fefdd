#pragma once
// Stack-based traversal of a flattened binary BVH, shared by the CPU and CUDA back ends.
// Children are visited nearest first; the farther one waits on an explicit stack.
#include "engine/bvh/layout/bvh_node.h"
#include "engine/bvh/traversal/node_slab_test.h"

namespace rtrt {

// What the heatmap view shows (the paper's Figure 7): work done for one ray.
struct TraversalStats {
    uint32_t nodesVisited = 0;
    uint32_t primsTested = 0;
};

// The two queries of every traversal here: the closest hit (the Intersect* functions) or whether
// anything blocks the ray (the Occluded* functions, shadow rays).
enum class Query { kIntersect, kOccluded };

// One loop for both queries (as madmann91/bvh's intersect<IsAnyHit>). test(primIndex, tMax) tests
// one primitive. kIntersect: test returns true when it found a nearer hit, having recorded it;
// tMax shrinks to that hit's distance. kOccluded: test returns true when the primitive blocks the
// ray before tMax, and the traversal stops there; tMax stays, so children keep the builder's order.
template <Query kQuery, typename TestPrim>
RT_HD inline bool Traverse(const BvhNode* nodes, const RaySetup& ray, float& tMax, TestPrim&& test,
                           TraversalStats* stats) {
    float tRoot;
    if (stats) ++stats->nodesVisited;
    if (!SlabTest(nodes[0], ray, tMax, &tRoot)) return false;
    uint32_t stack[kBvhStackSize];
    uint32_t stackSize = 0;
    uint32_t current = 0;
    bool found = false;
    for (;;) {
        const BvhNode& node = nodes[current];
        if (node.IsLeaf()) {
            for (uint32_t i = 0; i < node.primCount; ++i) {
                if (stats) ++stats->primsTested;
                if (test(node.leftFirst + i, tMax)) {
                    if constexpr (kQuery == Query::kOccluded) return true;
                    found = true;
                }
            }
        } else {
            const uint32_t left = node.leftFirst;
            float tLeft, tRight;
            bool hitLeft = SlabTest(nodes[left], ray, tMax, &tLeft);
            bool hitRight = SlabTest(nodes[left + 1], ray, tMax, &tRight);
            if (stats) stats->nodesVisited += 2;
            if (hitLeft && hitRight) {
                if constexpr (kQuery == Query::kIntersect) {
                    uint32_t nearChild = tLeft <= tRight ? left : left + 1;
                    stack[stackSize++] = tLeft <= tRight ? left + 1 : left;
                    current = nearChild;
                } else {
                    stack[stackSize++] = left + 1;
                    current = left;
                }
                continue;
            }
            if (hitLeft || hitRight) {
                current = hitLeft ? left : left + 1;
                continue;
            }
        }
        if (stackSize == 0) break;
        current = stack[--stackSize];
    }
    return found;
}

}  // namespace rtrt
