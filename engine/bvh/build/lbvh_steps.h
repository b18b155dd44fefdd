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

// How the sorted primitives fill the leaves: leaf j holds slots [size j, size j + size), the last
// leaf what remains. The TLAS puts two instances in a leaf (tlas.h); other trees one primitive.
struct LbvhLeafGroups {
    uint32_t primCount;
    uint32_t size;

    RT_HD uint32_t LeafCount() const { return (primCount + size - 1) / size; }
    RT_HD uint32_t First(uint32_t leaf) const { return leaf * size; }
    RT_HD uint32_t Count(uint32_t leaf) const {
        const uint32_t rest = primCount - First(leaf);
        return rest < size ? rest : size;
    }
};

// The leaf over slots [first, first + count): its box is the union of theirs.
template <class Boxes>
RT_HD inline BvhNode LbvhLeaf(const Boxes& bounds, const uint32_t* primOrder, uint32_t first,
                              uint32_t count) {
    Aabb box = bounds[primOrder[first]];
    for (uint32_t s = 1; s < count; ++s) box.Grow(Aabb(bounds[primOrder[first + s]]));
    BvhNode node;
    node.SetBounds(box);
    node.leftFirst = first;
    node.primCount = count;
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

// A tree of one leaf: the root is that leaf.
template <class Boxes>
struct LbvhRootLeaf {
    Boxes bounds;
    const uint32_t* primOrder;
    uint32_t primCount;
    BvhNode* nodes;
    RT_HD void operator()(size_t) const { nodes[0] = LbvhLeaf(bounds, primOrder, 0, primCount); }
};

// The sort key of each leaf, for Karras's nodes over leaves: its first primitive's code (the
// sorted codes are in order, so the leaves' are too).
struct LbvhLeafCodes {
    const uint32_t* sortedCodes;
    LbvhLeafGroups groups;
    uint32_t* leafCodes;
    RT_HD void operator()(size_t j) const { leafCodes[j] = sortedCodes[groups.First(uint32_t(j))]; }
};

// Karras internal node k (over the leaves' codes) writes its leaf children at 2 + 2k and 3 + 2k
// and tells its internal children where they sit.
template <class Boxes>
struct LbvhKarrasNodes {
    const uint32_t* leafCodes;  // sorted, one per leaf
    LbvhLeafGroups groups;
    const uint32_t* primOrder;
    Boxes bounds;
    BvhNode* nodes;
    uint32_t* positionOf;
    RT_HD BvhNode Leaf(uint32_t j) const {
        return LbvhLeaf(bounds, primOrder, groups.First(j), groups.Count(j));
    }
    RT_HD void operator()(size_t i) const {
        const uint32_t k = uint32_t(i);
        const KarrasNode range = KarrasInternalNode(leafCodes, groups.LeafCount(), k);
        const uint32_t pair = 2 + 2 * k;
        if (range.split == range.first)
            nodes[pair] = Leaf(range.split);
        else
            positionOf[range.split] = pair;
        if (range.split + 1 == range.last)
            nodes[pair + 1] = Leaf(range.split + 1);
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

// A refit's leaves take their primitives' new boxes (positions from 2; the root is never a leaf
// here).
template <class Boxes>
struct LbvhRefitLeaves {
    Boxes bounds;
    const uint32_t* primOrder;
    BvhNode* nodes;
    RT_HD void operator()(size_t i) const {
        const size_t p = i + 2;
        const BvhNode node = nodes[p];
        if (node.IsLeaf()) nodes[p] = LbvhLeaf(bounds, primOrder, node.leftFirst, node.primCount);
    }
};

// Bounds of every interior node from its children: each leaf walks up; at each parent the first
// arrival stops and the second, which then sees both children done, computes the bounds.
struct LbvhBoundsBottomUp {
    const uint32_t* parents;
    BvhNode* nodes;
    uint32_t* arrivals;  // zero per position before the pass

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
            if (Arrive(&arrivals[p]) == 0) return;  // the sibling's walk finishes p
            const uint32_t left = nodes[p].leftFirst;
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
