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

// Closest hit. intersect(primIndex, tMax) tests one primitive and returns true when it found a
// nearer hit, having recorded it; tMax shrinks to that hit's distance.
template <typename IntersectPrim>
RT_HD inline bool TraverseClosest(const BvhNode* nodes, const RaySetup& ray, float& tMax,
                                  IntersectPrim&& intersect, TraversalStats* stats) {
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
                if (intersect(node.leftFirst + i, tMax)) found = true;
            }
        } else {
            const uint32_t left = node.leftFirst;
            float tLeft, tRight;
            bool hitLeft = SlabTest(nodes[left], ray, tMax, &tLeft);
            bool hitRight = SlabTest(nodes[left + 1], ray, tMax, &tRight);
            if (stats) stats->nodesVisited += 2;
            if (hitLeft && hitRight) {
                uint32_t nearChild = tLeft <= tRight ? left : left + 1;
                stack[stackSize++] = tLeft <= tRight ? left + 1 : left;
                current = nearChild;
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

// Any hit (shadow rays): stops at the first primitive that occludes before tMax.
template <typename OccludesPrim>
RT_HD inline bool TraverseAny(const BvhNode* nodes, const RaySetup& ray, float tMax,
                              OccludesPrim&& occludes, TraversalStats* stats) {
    float tEntry;
    if (stats) ++stats->nodesVisited;
    if (!SlabTest(nodes[0], ray, tMax, &tEntry)) return false;
    uint32_t stack[kBvhStackSize];
    uint32_t stackSize = 0;
    uint32_t current = 0;
    for (;;) {
        const BvhNode& node = nodes[current];
        if (node.IsLeaf()) {
            for (uint32_t i = 0; i < node.primCount; ++i) {
                if (stats) ++stats->primsTested;
                if (occludes(node.leftFirst + i, tMax)) return true;
            }
        } else {
            const uint32_t left = node.leftFirst;
            float tLeft, tRight;
            bool hitLeft = SlabTest(nodes[left], ray, tMax, &tLeft);
            bool hitRight = SlabTest(nodes[left + 1], ray, tMax, &tRight);
            if (stats) stats->nodesVisited += 2;
            if (hitLeft && hitRight) {
                stack[stackSize++] = left + 1;
                current = left;
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
    return false;
}

}  // namespace rtrt
