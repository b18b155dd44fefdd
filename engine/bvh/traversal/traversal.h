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

// Whether pred holds for any active lane of the warp; on the CPU, one lane.
RT_HD inline bool AnyLane(bool pred) {
#if defined(__CUDA_ARCH__)
    return __any_sync(__activemask(), pred);
#else
    return pred;
#endif
}

// Speculative traversal (Aila and Laine 2009) on the GPU: a lane that reaches a leaf sets it aside
// and keeps descending until every lane of the warp holds a leaf, so that the warp intersects
// leaves with more lanes at once. RTRT_BLAS_SPECULATION=0 turns it off, for experiments.
#if !defined(RTRT_BLAS_SPECULATION)
#define RTRT_BLAS_SPECULATION 1
#endif
#if defined(__CUDA_ARCH__)
inline constexpr bool kSpeculativeTraversal = RTRT_BLAS_SPECULATION != 0;
#else
inline constexpr bool kSpeculativeTraversal = false;
#endif

// One loop for both queries (as madmann91/bvh's intersect<IsAnyHit>). test(primIndex, tMax) tests
// one primitive. kIntersect: test returns true when it found a nearer hit, having recorded it;
// tMax shrinks to that hit's distance. kOccluded: test returns true when the primitive blocks the
// ray before tMax, and the traversal stops there; tMax stays, so children keep the builder's order.
//
// The loop has the while-while form of Aila and Laine (2009): a lane steps through interior nodes
// until it holds a leaf, and leaves are intersected once every lane of the warp has left the
// interior loop. In the if-else form (a leaf or a node pair per iteration) a GPU warp ran each
// leaf's triangle tests with about 3 of its lanes, as the other lanes were still between nodes
// (bench/results/trace-profile-h200-2026-12-03.txt). A lane visits nodes and leaves in the same
// order in both forms; speculation (above) adds only box tests made against a larger tMax, and is
// off when stats are counted, so that the heatmap's counts are the CPU's. On one lane (the CPU, or
// a test with kSpeculate) speculation sets a leaf aside and intersects it at once.
template <Query kQuery, bool kSpeculate = kSpeculativeTraversal, typename TestPrim>
RT_HD inline bool Traverse(const BvhNode* nodes, const RaySetup& ray, float& tMax, TestPrim&& test,
                           TraversalStats* stats) {
    float tRoot;
    NodeHeader current;  // of the node in hand; the stack holds the headers of those waiting
    if (stats) ++stats->nodesVisited;
    if (!SlabTest(nodes[0], ray, tMax, &tRoot, &current)) return false;
    NodeHeader stack[kBvhStackSize];
    uint32_t stackSize = 0;
    bool holding = true;  // current is a node still to visit
    const bool speculate = kSpeculate && stats == nullptr;
    NodeHeader postponed{0, 0};  // a leaf set aside while speculating
    bool hasPostponed = false;
    bool found = false;
    for (;;) {
        while (holding) {
            if (current.IsLeaf()) {
                if (!speculate || hasPostponed) break;
                postponed = current;
                hasPostponed = true;
                holding = stackSize > 0;
                if (holding) current = stack[--stackSize];
            } else {
                const uint32_t left = current.leftFirst;
                float tLeft, tRight;
                NodeHeader headLeft, headRight;
                const bool hitLeft = SlabTest(nodes[left], ray, tMax, &tLeft, &headLeft);
                const bool hitRight = SlabTest(nodes[left + 1], ray, tMax, &tRight, &headRight);
                if (stats) stats->nodesVisited += 2;
                if (hitLeft && hitRight) {
                    // kIntersect visits the nearer child first; kOccluded the builder's order.
                    const bool leftNearer = kQuery == Query::kOccluded || tLeft <= tRight;
                    stack[stackSize++] = leftNearer ? headRight : headLeft;
                    current = leftNearer ? headLeft : headRight;
                } else if (hitLeft || hitRight) {
                    current = hitLeft ? headLeft : headRight;
                } else {
                    holding = stackSize > 0;
                    if (holding) current = stack[--stackSize];
                }
            }
            if (speculate && !AnyLane(holding && !hasPostponed)) break;
        }
        // The leaf set aside comes first: it was found first.
        NodeHeader leaf;
        if (hasPostponed) {
            leaf = postponed;
            hasPostponed = false;
        } else if (holding) {
            leaf = current;
            holding = stackSize > 0;
            if (holding) current = stack[--stackSize];
        } else {
            break;
        }
        for (uint32_t i = 0; i < leaf.primCount; ++i) {
            if (stats) ++stats->primsTested;
            if (test(leaf.leftFirst + i, tMax)) {
                if constexpr (kQuery == Query::kOccluded) return true;
                found = true;
            }
        }
    }
    return found;
}

}  // namespace rtrt
