#pragma once
// The per-item steps of the LBVH build and refit (lbvh.h), written once: BuildLbvh runs them over
// TBB, GpuLbvh over CUDA threads, through engine/core's ParallelFor, so the GPU tree equals the
// CPU tree bit for bit. Each step is a function object over one index.
#include "engine/bvh/build/karras.h"
#include "engine/bvh/build/morton.h"
#include "engine/bvh/layout/bvh_node.h"

#if !defined(__CUDA_ARCH__)
#include <atomic>
#endif

namespace rtrt {

inline constexpr uint32_t kLbvhNoParent = UINT32_MAX;

RT_HD inline BvhNode LbvhLeaf(const Aabb& bounds, uint32_t slot) {
    BvhNode node;
    node.SetBounds(bounds);
    node.leftFirst = slot;
    node.primCount = 1;
    return node;
}

// The steps read the primitives' boxes through Boxes: an array (const Aabb*), or anything whose
// operator[] gives box i, such as boxes computed where they are read (the TLAS's instances:
// InstanceWorldBoxes, tlas.h), which spares an array of them.

// The Morton code of each primitive's centroid, and its index (the sort's payload). The centroids'
// bounds: an Aabb, or anything that converts to one (the GPU's OrderedBounds).
template <class Boxes, class CentroidBounds = Aabb>
struct LbvhMortonCodes {
    Boxes bounds;
    const CentroidBounds* centroidBounds;
    uint32_t* codes;
    uint32_t* indices;
    RT_HD void operator()(size_t i) const {
        codes[i] = MortonCode(Aabb(bounds[i]).Centroid(), Aabb(*centroidBounds));
        indices[i] = uint32_t(i);
    }
};

// A tree of one primitive: the root is its leaf.
template <class Boxes>
struct LbvhRootLeaf {
    Boxes bounds;
    const uint32_t* primOrder;
    BvhNode* nodes;
    RT_HD void operator()(size_t) const { nodes[0] = LbvhLeaf(bounds[primOrder[0]], 0); }
};

// Karras internal node k writes its leaf children at 2 + 2k and 3 + 2k and tells its internal
// children where they sit.
template <class Boxes>
struct LbvhKarrasNodes {
    const uint32_t* codes;  // sorted
    uint32_t n;
    const uint32_t* primOrder;
    Boxes bounds;
    BvhNode* nodes;
    uint32_t* positionOf;
    RT_HD void operator()(size_t i) const {
        const uint32_t k = uint32_t(i);
        const KarrasNode range = KarrasInternalNode(codes, n, k);
        const uint32_t pair = 2 + 2 * k;
        if (range.split == range.first)
            nodes[pair] = LbvhLeaf(bounds[primOrder[range.split]], range.split);
        else
            positionOf[range.split] = pair;
        if (range.split + 1 == range.last)
            nodes[pair + 1] = LbvhLeaf(bounds[primOrder[range.split + 1]], range.split + 1);
        else
            positionOf[range.split + 1] = pair + 1;
    }
};

// Internal node k, now at its position (the root at 0), points at its children and they at it.
struct LbvhLinkNodes {
    const uint32_t* positionOf;
    BvhNode* nodes;
    uint32_t* parents;
    RT_HD void operator()(size_t i) const {
        const uint32_t k = uint32_t(i);
        const uint32_t position = k == 0 ? 0 : positionOf[k];
        const uint32_t pair = 2 + 2 * k;
        nodes[position].leftFirst = pair;
        nodes[position].primCount = 0;
        parents[pair] = parents[pair + 1] = position;
    }
};

// A refit's leaves take their primitive's new box (positions from 2; the root is never a leaf
// here).
template <class Boxes>
struct LbvhRefitLeaves {
    Boxes bounds;
    const uint32_t* primOrder;
    BvhNode* nodes;
    RT_HD void operator()(size_t i) const {
        const size_t p = i + 2;
        if (nodes[p].IsLeaf()) nodes[p].SetBounds(bounds[primOrder[nodes[p].leftFirst]]);
    }
};

// An interior node's arrival counter is found by its children's pair (left child at 2 + 2k:
// counter k), so a tree of the pair layout needs one per pair, not one per position.
RT_HD inline uint32_t LbvhArrivalIndex(uint32_t leftChild) { return (leftChild - 2) / 2; }
RT_HD inline uint32_t LbvhArrivalCount(size_t positions) {
    return positions > 2 ? uint32_t((positions - 2) / 2) : 0u;
}

// Bounds of every interior node from its children: each leaf walks up; at each parent the first
// arrival stops and the second, which then sees both children done, computes the bounds.
struct LbvhBoundsBottomUp {
    const uint32_t* parents;
    BvhNode* nodes;
    uint32_t* arrivals;  // LbvhArrivalCount(positions) zeros before the pass

    // The arrival count before this one; this thread's writes below p are visible to the thread
    // that arrives second.
    RT_HD static uint32_t Arrive(uint32_t* counter) {
#if defined(__CUDA_ARCH__)
        __threadfence();
        return atomicAdd(counter, 1u);
#else
        return std::atomic_ref<uint32_t>(*counter).fetch_add(1, std::memory_order_acq_rel);
#endif
    }

    // A node another thread may just have written (on the GPU past the incoherent L1).
    RT_HD static Aabb LoadBounds(const BvhNode* node) {
#if defined(__CUDA_ARCH__)
        const float4* raw = reinterpret_cast<const float4*>(node);
        const float4 lo = __ldcg(raw), hi = __ldcg(raw + 1);
        return {vec3(lo.x, lo.y, lo.z), vec3(hi.x, hi.y, hi.z)};
#else
        return node->Bounds();
#endif
    }

    // The walk from one leaf (at any position but the root) towards the root. Any tree of the
    // pair layout with parent links works: the deforming BLASes' refit runs it too.
    RT_HD static void WalkUp(const uint32_t* parents, BvhNode* nodes, uint32_t* arrivals,
                             uint32_t leaf) {
        uint32_t p = parents[leaf];
        while (p != kLbvhNoParent) {
            const uint32_t left = nodes[p].leftFirst;  // not written by the walk
            // The sibling's walk finishes p.
            if (Arrive(&arrivals[LbvhArrivalIndex(left)]) == 0) return;
            Aabb b = LoadBounds(&nodes[left]);
            b.Grow(LoadBounds(&nodes[left + 1]));
            nodes[p].boundsMin = b.min;
            nodes[p].boundsMax = b.max;
            p = parents[p];
        }
    }

    RT_HD void operator()(size_t i) const {
        const uint32_t leaf = uint32_t(i + 2);
        if (nodes[leaf].IsLeaf()) WalkUp(parents, nodes, arrivals, leaf);
    }
};

}  // namespace rtrt
