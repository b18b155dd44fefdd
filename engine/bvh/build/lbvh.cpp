#include "engine/bvh/build/lbvh.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <numeric>

#include "engine/bvh/build/morton.h"
#include "engine/core/parallel_for.h"

namespace rtrt {
namespace {

constexpr uint32_t kNoParent = UINT32_MAX;

BvhNode LeafNode(const Aabb& bounds, uint32_t slot) {
    BvhNode node;
    node.SetBounds(bounds);
    node.leftFirst = slot;
    node.primCount = 1;
    return node;
}

// Bounds of every interior node from its children: each leaf walks up; at each parent the first
// arrival stops and the second (which then sees both children done) computes the bounds.
void BoundsBottomUp(Lbvh& bvh) {
    const size_t positions = bvh.nodes.size();
    std::unique_ptr<std::atomic<uint32_t>[]> arrivals(new std::atomic<uint32_t>[positions]);
    for (size_t p = 0; p < positions; ++p) arrivals[p].store(0, std::memory_order_relaxed);
    ParallelFor(2, positions, 1024, [&](size_t leaf) {
        if (!bvh.nodes[leaf].IsLeaf()) return;
        uint32_t p = bvh.parents[leaf];
        while (p != kNoParent) {
            if (arrivals[p].fetch_add(1, std::memory_order_acq_rel) == 0) return;
            BvhNode& node = bvh.nodes[p];
            Aabb b = bvh.nodes[node.leftFirst].Bounds();
            b.Grow(bvh.nodes[node.leftFirst + 1].Bounds());
            node.SetBounds(b);
            p = bvh.parents[p];
        }
    });
}

}  // namespace

Lbvh BuildLbvh(std::span<const Aabb> primBounds) {
    Lbvh bvh;
    const uint32_t n = uint32_t(primBounds.size());
    if (n == 0) {
        bvh.nodes.resize(2, BvhNode{vec3(kInfinity), 0, vec3(-kInfinity), 0});
        bvh.parents.assign(2, kNoParent);
        return bvh;
    }
    Aabb centroidBounds;
    for (const Aabb& b : primBounds) centroidBounds.Grow(b.Centroid());
    std::vector<uint64_t> keys(n);  // Morton code << 32 | primitive: equal codes keep input order
    ParallelFor(0, n, 4096, [&](size_t i) {
        keys[i] = (uint64_t(MortonCode(primBounds[i].Centroid(), centroidBounds)) << 32) | i;
    });
    std::sort(keys.begin(), keys.end());
    std::vector<uint32_t> codes(n);
    bvh.primOrder.resize(n);
    for (uint32_t s = 0; s < n; ++s) {
        codes[s] = uint32_t(keys[s] >> 32);
        bvh.primOrder[s] = uint32_t(keys[s]);
    }

    bvh.nodes.resize(2 * size_t(n));
    bvh.parents.assign(bvh.nodes.size(), kNoParent);
    bvh.nodes[1] = BvhNode{vec3(0), 0, vec3(0), 0};
    if (n == 1) {
        bvh.nodes[0] = LeafNode(primBounds[bvh.primOrder[0]], 0);
        return bvh;
    }
    // Internal node k sits where its parent put it: position 0 for the root, else a child slot.
    std::vector<uint32_t> positionOf(n - 1, 0);
    ParallelFor(0, n - 1, 1024, [&](size_t k) {
        const KarrasNode range = KarrasInternalNode(codes.data(), n, uint32_t(k));
        const uint32_t pair = 2 + 2 * uint32_t(k);
        const uint32_t children[2] = {range.split, range.split + 1};
        const bool isLeaf[2] = {range.split == range.first, range.split + 1 == range.last};
        for (int c = 0; c < 2; ++c) {
            if (isLeaf[c])
                bvh.nodes[pair + c] = LeafNode(primBounds[bvh.primOrder[children[c]]], children[c]);
            else
                positionOf[children[c]] = pair + c;
        }
    });
    ParallelFor(0, n - 1, 1024, [&](size_t k) {
        const uint32_t position = positionOf[k];
        const uint32_t pair = 2 + 2 * uint32_t(k);
        bvh.nodes[position].leftFirst = pair;
        bvh.nodes[position].primCount = 0;
        bvh.parents[pair] = bvh.parents[pair + 1] = position;
    });
    BoundsBottomUp(bvh);
    return bvh;
}

void RefitLbvh(Lbvh& bvh, std::span<const Aabb> primBounds) {
    if (bvh.primOrder.empty()) return;
    if (bvh.nodes[0].IsLeaf()) {
        bvh.nodes[0].SetBounds(primBounds[bvh.primOrder[0]]);
        return;
    }
    ParallelFor(2, bvh.nodes.size(), 4096, [&](size_t p) {
        BvhNode& node = bvh.nodes[p];
        if (node.IsLeaf()) node.SetBounds(primBounds[bvh.primOrder[node.leftFirst]]);
    });
    BoundsBottomUp(bvh);
}

}  // namespace rtrt
