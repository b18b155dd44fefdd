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

// What an LBVH's leaves hold: the slot (sorted position) of their primitive, for trees whose
// primitives are then stored in leaf order (BLASes: primOrder maps slots to primitives), or the
// primitive's own index, for trees that keep no order at all (TLASes: the instance).
enum class LbvhLeaves : uint8_t { kSlots, kPrimitiveIds };

RT_HD inline BvhNode LbvhLeaf(const Aabb& bounds, uint32_t index) {
    BvhNode node;
    node.SetBounds(bounds);
    node.leftFirst = index;
    node.primCount = 1;
    return node;
}

// An interior node whose children sit at leftChild and leftChild + 1; its bounds come bottom-up.
RT_HD inline BvhNode LbvhInterior(uint32_t leftChild) {
    BvhNode node;
    node.SetBounds(Aabb{});
    node.leftFirst = leftChild;
    node.primCount = 0;
    return node;
}

// The steps read the primitives' boxes through Boxes: an array (const Aabb*), or anything whose
// operator[] gives box i, such as boxes computed where they are read (the TLAS's instances:
// InstanceWorldBoxes, tlas.h), which spares an array of them. The sorted codes (Codes) and the
// leaf order (Order) are read the same way: arrays, or words kept elsewhere (the GPU TLAS keeps
// them in the instance records, gpu_tlas.h).

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

// The leaf of sorted primitive s.
template <class Boxes, class Order>
RT_HD inline BvhNode LbvhLeafOf(Boxes bounds, Order primOrder, LbvhLeaves leaves, uint32_t s) {
    const uint32_t prim = primOrder[s];
    return LbvhLeaf(bounds[prim], leaves == LbvhLeaves::kSlots ? s : prim);
}

// A tree of one primitive: the root is its leaf.
template <class Boxes, class Order = const uint32_t*>
struct LbvhRootLeaf {
    Boxes bounds;
    Order primOrder;
    BvhNode* nodes;
    LbvhLeaves leaves = LbvhLeaves::kSlots;
    RT_HD void operator()(size_t) const { nodes[0] = LbvhLeafOf(bounds, primOrder, leaves, 0); }
};

// Karras internal node k writes its two children at 2 + 2k and 3 + 2k: a leaf, or internal node
// c, whose own children will sit at 2 + 2c. The root (k = 0) also writes itself at position 0.
template <class Boxes, class Codes = const uint32_t*, class Order = const uint32_t*>
struct LbvhKarrasNodes {
    Codes codes;  // sorted
    uint32_t n;
    Order primOrder;
    Boxes bounds;
    BvhNode* nodes;
    LbvhLeaves leaves = LbvhLeaves::kSlots;

    RT_HD BvhNode Child(uint32_t index, bool leaf) const {
        return leaf ? LbvhLeafOf(bounds, primOrder, leaves, index) : LbvhInterior(2 + 2 * index);
    }
    RT_HD void operator()(size_t i) const {
        const uint32_t k = uint32_t(i);
        const KarrasNode range = KarrasInternalNode(codes, n, k);
        const uint32_t pair = 2 + 2 * k;
        if (k == 0) nodes[0] = LbvhInterior(2);
        nodes[pair] = Child(range.split, range.split == range.first);
        nodes[pair + 1] = Child(range.split + 1, range.split + 1 == range.last);
    }
};

// Parent links by position, one per node (Lbvh::parents; the deformers' trees).
struct LbvhPositionParents {
    uint32_t* parents;  // the root's is kLbvhNoParent
    RT_HD uint32_t Of(uint32_t position) const { return parents[position]; }
    RT_HD void SetPair(uint32_t leftChild, uint32_t parent) const {
        parents[leftChild] = parents[leftChild + 1] = parent;
    }
};

// Parent links by pair: the two children of Karras node k (at 2 + 2k) share their parent, so n - 1
// words hold every link; Words is any array of them.
template <class Words>
struct LbvhPairParents {
    Words words;
    RT_HD uint32_t Of(uint32_t position) const {
        return position < 2 ? kLbvhNoParent : uint32_t(words[(position - 2) / 2]);
    }
    RT_HD void SetPair(uint32_t leftChild, uint32_t parent) const {
        words[(leftChild - 2) / 2] = parent;
    }
};

// Each interior node at a position (the root at 0; position 1 is unused) tells its children it is
// their parent.
template <class Parents>
struct LbvhLinkNodes {
    const BvhNode* nodes;
    Parents parents;
    RT_HD void operator()(size_t i) const {
        const uint32_t position = uint32_t(i);
        if (position == 1 || nodes[position].IsLeaf()) return;
        parents.SetPair(nodes[position].leftFirst, position);
    }
};

// A refit's leaves take their primitive's new box (positions from 2; the root is never a leaf
// here).
template <class Boxes, class Order = const uint32_t*>
struct LbvhRefitLeaves {
    Boxes bounds;
    Order primOrder;  // read only for leaves that hold slots
    BvhNode* nodes;
    LbvhLeaves leaves = LbvhLeaves::kSlots;
    RT_HD void operator()(size_t i) const {
        BvhNode& node = nodes[i + 2];
        if (!node.IsLeaf()) return;
        const uint32_t prim =
            leaves == LbvhLeaves::kSlots ? uint32_t(primOrder[node.leftFirst]) : node.leftFirst;
        node.SetBounds(bounds[prim]);
    }
};

// The bottom-up walk's mark on an interior node that one of its children has reached: the top bit
// of its leftFirst, which child positions (below 2^31) never use. The second arrival clears it,
// so a finished walk leaves every node's indices as it found them and needs no counters.
inline constexpr uint32_t kLbvhArrived = 0x80000000u;

// Bounds of every interior node from its children: each leaf walks up; at each parent the first
// arrival stops and the second, which then sees both children done, computes the bounds. Any tree
// of the pair layout with parent links works (Parents: LbvhPositionParents or LbvhPairParents):
// the deforming BLASes' refit runs it too.
template <class Parents>
struct LbvhBoundsBottomUp {
    Parents parents;
    BvhNode* nodes;

    // Marks *leftFirst and returns it as it was; this thread's writes below the node are visible
    // to the thread that arrives second.
    RT_HD static uint32_t Arrive(uint32_t* leftFirst) {
#if defined(__CUDA_ARCH__)
        __threadfence();
        return atomicOr(leftFirst, kLbvhArrived);
#else
        return std::atomic_ref<uint32_t>(*leftFirst)
            .fetch_or(kLbvhArrived, std::memory_order_acq_rel);
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

    // The walk from one leaf (at any position but the root) towards the root.
    RT_HD static void WalkUp(Parents parents, BvhNode* nodes, uint32_t leaf) {
        uint32_t p = parents.Of(leaf);
        while (p != kLbvhNoParent) {
            const uint32_t before = Arrive(&nodes[p].leftFirst);
            if ((before & kLbvhArrived) == 0) return;  // the sibling's walk finishes p
            const uint32_t left = before & ~kLbvhArrived;
            nodes[p].leftFirst = left;  // both arrivals are in: no other thread touches it
            Aabb b = LoadBounds(&nodes[left]);
            b.Grow(LoadBounds(&nodes[left + 1]));
            nodes[p].boundsMin = b.min;
            nodes[p].boundsMax = b.max;
            p = parents.Of(p);
        }
    }

    RT_HD void operator()(size_t i) const {
        const uint32_t leaf = uint32_t(i + 2);
        if (nodes[leaf].IsLeaf()) WalkUp(parents, nodes, leaf);
    }
};

}  // namespace rtrt
