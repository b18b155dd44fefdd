#pragma once
// Linear BVH over instance bounds, rebuilt every frame: Morton codes, a sort, the hierarchy of
// Karras 2012 ("Maximizing Parallelism in the Construction of BVHs, Octrees, and k-d Trees"),
// bottom-up bounds. The CPU version here runs the same steps the CUDA version runs per thread.
//
// Layout in the common BvhNode array: the root at 0 (index 1 unused), and the two children of
// Karras internal node k at 2 + 2k and 3 + 2k. Leaf slot s holds sorted primitive s: its slot
// (LbvhLeaves::kSlots) or the primitive's index (kPrimitiveIds, for the TLAS).
#include <span>
#include <vector>

#include "engine/bvh/build/karras.h"
#include "engine/bvh/build/lbvh_steps.h"
#include "engine/bvh/layout/bvh_node.h"

namespace rtrt {

struct Lbvh {
    AlignedVector<BvhNode> nodes;
    std::vector<uint32_t> primOrder;  // leaf slot -> primitive index (sorted by Morton code)
    std::vector<uint32_t> parents;    // node position -> parent position (root: UINT32_MAX)
    LbvhLeaves leaves = LbvhLeaves::kSlots;
};

Lbvh BuildLbvh(std::span<const Aabb> primBounds, LbvhLeaves leaves = LbvhLeaves::kSlots);

// Recomputes bounds bottom-up for a new set of primitive bounds (same primitives, moved); the
// topology stays.
void RefitLbvh(Lbvh& bvh, std::span<const Aabb> primBounds);

}  // namespace rtrt
