// The LBVH (Karras 2012) over instance bounds: every primitive reachable exactly once, every node
// bounds its children, equal Morton codes and zero-extent inputs handled, refit keeps it valid.
#include "engine/bvh/build/lbvh.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "engine/bvh/build/morton.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

// Walks the tree: each slot once, bounds nested, depth within the traversal stack.
void ExpectValid(const Lbvh& bvh, std::span<const Aabb> boxes) {
    const uint32_t n = uint32_t(boxes.size());
    ASSERT_EQ(bvh.primOrder.size(), n);
    std::vector<uint32_t> seen(n, 0);
    struct Item {
        uint32_t node, depth;
    };
    std::vector<Item> stack{{0, 0}};
    uint32_t maxDepth = 0;
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        const BvhNode& node = bvh.nodes[item.node];
        maxDepth = std::max(maxDepth, item.depth);
        if (node.IsLeaf()) {
            ASSERT_EQ(node.primCount, 1u);
            ASSERT_LT(node.leftFirst, n);
            ++seen[node.leftFirst];
            EXPECT_TRUE(node.Bounds().Contains(boxes[bvh.primOrder[node.leftFirst]]));
            continue;
        }
        for (uint32_t c = 0; c < 2; ++c) {
            const uint32_t child = node.leftFirst + c;
            ASSERT_LT(child, bvh.nodes.size());
            EXPECT_TRUE(node.Bounds().Contains(bvh.nodes[child].Bounds())) << "node " << item.node;
            EXPECT_EQ(bvh.parents[child], item.node);
            stack.push_back({child, item.depth + 1});
        }
    }
    for (uint32_t s = 0; s < n; ++s) EXPECT_EQ(seen[s], 1u) << "slot " << s;
    EXPECT_LT(maxDepth, kBvhStackSize);
}

TEST(Morton, InterleavesBitsXYZ) {
    EXPECT_EQ(Morton3(1, 0, 0), 4u);
    EXPECT_EQ(Morton3(0, 1, 0), 2u);
    EXPECT_EQ(Morton3(0, 0, 1), 1u);
    EXPECT_EQ(Morton3(1023, 1023, 1023), (1u << 30) - 1);
    EXPECT_EQ(Morton3(2, 0, 0), 32u);
}

TEST(Morton, FlatAndNanInputsMapToZero) {
    const Aabb flat{vec3(0), vec3(0, 1, 1)};
    EXPECT_EQ(MortonCode(vec3(0, 0, 0), flat), 0u);
    EXPECT_EQ(MortonCode(vec3(0, 1, 1), flat), Morton3(0, 1023, 1023));
    EXPECT_EQ(MortonCode(vec3(std::nanf(""), 0, 0), Aabb{vec3(-1), vec3(1)}), Morton3(0, 511, 511));
}

TEST(Lbvh, ValidForSmallAndLargeCounts) {
    for (uint32_t n : {0u, 1u, 2u, 3u, 7u, 1000u, 100000u}) {
        SCOPED_TRACE(n);
        const std::vector<Aabb> boxes = test::RandomBoxes(n, 50.0f, n);
        const Lbvh bvh = BuildLbvh(boxes);
        if (n == 0) {
            EXPECT_TRUE(bvh.nodes[0].Bounds().IsEmpty());
            continue;
        }
        ExpectValid(bvh, boxes);
        EXPECT_EQ(bvh.nodes.size(), 2u * n);
    }
}

TEST(Lbvh, AllInstancesAtOnePoint) {
    // Equal Morton codes everywhere: the tree splits on the index bits, depth ~ log2(n).
    const std::vector<Aabb> boxes(4096, Aabb{vec3(1, 2, 3), vec3(1, 2, 3)});
    const Lbvh bvh = BuildLbvh(boxes);
    ExpectValid(bvh, boxes);
}

TEST(Lbvh, OneFarOutlier) {
    std::vector<Aabb> boxes = test::RandomBoxes(1000, 1.0f, 9);
    boxes.push_back({vec3(1e7f), vec3(1e7f + 1.0f)});
    ExpectValid(BuildLbvh(boxes), boxes);
}

TEST(Lbvh, KarrasRootCoversEverything) {
    const std::vector<uint32_t> codes{1, 2, 4, 5, 19, 24, 25, 30};  // the paper's Figure 3
    const KarrasNode root = KarrasInternalNode(codes.data(), uint32_t(codes.size()), 0);
    EXPECT_EQ(root.first, 0u);
    EXPECT_EQ(root.last, 7u);
    EXPECT_EQ(root.split, 3u);  // 00101 | 10011: the first bit that differs
    const KarrasNode left = KarrasInternalNode(codes.data(), uint32_t(codes.size()), 3);
    EXPECT_EQ(left.first, 0u);
    EXPECT_EQ(left.last, 3u);
}

TEST(Lbvh, RefitFollowsMovedBoxes) {
    std::vector<Aabb> boxes = test::RandomBoxes(5000, 20.0f, 4);
    Lbvh bvh = BuildLbvh(boxes);
    for (Aabb& b : boxes) {
        b.min += vec3(3, -1, 0.5f);
        b.max += vec3(3.5f, -1, 0.5f);
    }
    RefitLbvh(bvh, boxes);
    ExpectValid(bvh, boxes);
}

// The TLAS's form: the same tree, but each leaf holds its primitive's index instead of its slot;
// a refit reads the boxes by those indices, and its walk leaves no mark on any node.
TEST(Lbvh, LeavesMayHoldPrimitiveIds) {
    std::vector<Aabb> boxes = test::RandomBoxes(3000, 20.0f, 8);
    const Lbvh slots = BuildLbvh(boxes);
    Lbvh ids = BuildLbvh(boxes, LbvhLeaves::kPrimitiveIds);
    auto expectSameButLeaves = [&](const Lbvh& a, const Lbvh& b) {
        ASSERT_EQ(a.nodes.size(), b.nodes.size());
        EXPECT_EQ(a.parents, b.parents);
        for (size_t i = 0; i < a.nodes.size(); ++i) {
            BvhNode expected = a.nodes[i];
            if (expected.IsLeaf()) expected.leftFirst = a.primOrder[expected.leftFirst];
            ASSERT_EQ(std::memcmp(&expected, &b.nodes[i], sizeof(BvhNode)), 0) << "node " << i;
        }
    };
    expectSameButLeaves(slots, ids);
    for (Aabb& b : boxes) b.max += vec3(0.5f, 0.0f, 2.0f);
    Lbvh refit = slots;
    RefitLbvh(refit, boxes);
    RefitLbvh(ids, boxes);
    expectSameButLeaves(refit, ids);
    for (const BvhNode& node : ids.nodes)
        if (!node.IsLeaf()) {
            EXPECT_LT(node.leftFirst, ids.nodes.size());
        }
}

}  // namespace
}  // namespace rtrt
