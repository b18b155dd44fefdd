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
    NodeHeader current;  // of the node in hand; the stack holds the headers of those waiting
    if (stats) ++stats->nodesVisited;
    if (!SlabTest(nodes[0], ray, tMax, &tRoot, &current)) return false;
    NodeHeader stack[kBvhStackSize];
    uint32_t stackSize = 0;
    bool found = false;
    for (;;) {
        if (current.IsLeaf()) {
            for (uint32_t i = 0; i < current.primCount; ++i) {
                if (stats) ++stats->primsTested;
                if (test(current.leftFirst + i, tMax)) {
                    if constexpr (kQuery == Query::kOccluded) return true;
                    found = true;
                }
            }
        } else {
            const uint32_t left = current.leftFirst;
            float tLeft, tRight;
            NodeHeader headLeft, headRight;
            bool hitLeft = SlabTest(nodes[left], ray, tMax, &tLeft, &headLeft);
            bool hitRight = SlabTest(nodes[left + 1], ray, tMax, &tRight, &headRight);
            if (stats) stats->nodesVisited += 2;
            if (hitLeft && hitRight) {
                // kIntersect visits the nearer child first; kOccluded the builder's order.
                const bool leftNearer = kQuery == Query::kOccluded || tLeft <= tRight;
                stack[stackSize++] = leftNearer ? headRight : headLeft;
                current = leftNearer ? headLeft : headRight;
                continue;
            }
            if (hitLeft || hitRight) {
                current = hitLeft ? headLeft : headRight;
                continue;
            }
        }
        if (stackSize == 0) break;
        current = stack[--stackSize];
    }
    return found;
}

}  // namespace rtrt
