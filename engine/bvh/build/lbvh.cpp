#include "engine/bvh/build/lbvh.h"

#include <algorithm>
#include <vector>

#include "engine/bvh/build/lbvh_steps.h"
#include "engine/core/parallel_for.h"

namespace rtrt {
namespace {

void BoundsBottomUp(Lbvh& bvh) {
    ParallelFor(0, bvh.nodes.size() - 2, 1024,
                LbvhBoundsBottomUp<LbvhPositionParents>{{bvh.parents.data()}, bvh.nodes.data()});
}

}  // namespace

Lbvh BuildLbvh(std::span<const Aabb> primBounds, LbvhLeaves leaves) {
    Lbvh bvh;
    bvh.leaves = leaves;
    const uint32_t n = uint32_t(primBounds.size());
    if (n == 0) {
        bvh.nodes.resize(2, BvhNode{vec3(kInfinity), 0, vec3(-kInfinity), 0});
        bvh.parents.assign(2, kLbvhNoParent);
        return bvh;
    }
    Aabb centroidBounds;
    for (const Aabb& b : primBounds) centroidBounds.Grow(b.Centroid());
    std::vector<uint32_t> codes(n);
    bvh.primOrder.resize(n);
    ParallelFor(0, n, 4096,
                LbvhMortonCodes<const Aabb*>{primBounds.data(), &centroidBounds, codes.data(),
                                             bvh.primOrder.data()});
    // Sorted as (code, index) pairs: equal codes keep input order, as the GPU's stable radix sort.
    std::vector<uint64_t> keys(n);
    for (uint32_t i = 0; i < n; ++i) keys[i] = uint64_t(codes[i]) << 32 | bvh.primOrder[i];
    std::sort(keys.begin(), keys.end());
    for (uint32_t s = 0; s < n; ++s) {
        codes[s] = uint32_t(keys[s] >> 32);
        bvh.primOrder[s] = uint32_t(keys[s]);
    }

    bvh.nodes.resize(2 * size_t(n));
    bvh.parents.assign(bvh.nodes.size(), kLbvhNoParent);
    bvh.nodes[1] = BvhNode{vec3(0), 0, vec3(0), 0};
    if (n == 1) {
        LbvhRootLeaf<const Aabb*>{primBounds.data(), bvh.primOrder.data(), bvh.nodes.data(),
                                  leaves}(0);
        return bvh;
    }
    ParallelFor(0, n - 1, 1024,
                LbvhKarrasNodes<const Aabb*>{codes.data(), n, bvh.primOrder.data(),
                                             primBounds.data(), bvh.nodes.data(), leaves});
    ParallelFor(0, bvh.nodes.size(), 1024,
                LbvhLinkNodes<LbvhPositionParents>{bvh.nodes.data(), {bvh.parents.data()}});
    BoundsBottomUp(bvh);
    return bvh;
}

void RefitLbvh(Lbvh& bvh, std::span<const Aabb> primBounds) {
    if (bvh.primOrder.empty()) return;
    if (bvh.nodes[0].IsLeaf()) {
        LbvhRootLeaf<const Aabb*>{primBounds.data(), bvh.primOrder.data(), bvh.nodes.data(),
                                  bvh.leaves}(0);
        return;
    }
    ParallelFor(0, bvh.nodes.size() - 2, 4096,
                LbvhRefitLeaves<const Aabb*>{primBounds.data(), bvh.primOrder.data(),
                                             bvh.nodes.data(), bvh.leaves});
    BoundsBottomUp(bvh);
}

}  // namespace rtrt
