// The TLAS policy: rebuild on topology changes, refit while quality holds, rebuild once the SAH
// cost has drifted past the threshold; the tree stays valid over many frames of motion.
#include "engine/bvh/tlas/dynamic_tlas.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/bvh/build/bvh_builder.h"

namespace rtrt {
namespace {

std::vector<Instance> Grid(uint32_t side, float spacing) {
    std::vector<Instance> instances;
    for (uint32_t i = 0; i < side * side * side; ++i) {
        const vec3 p(float(i % side), float((i / side) % side), float(i / (side * side)));
        const glm::mat4 m = glm::translate(glm::mat4(1.0f), spacing * p);
        Instance inst{};
        SetTransform(inst, m);
        instances.push_back(inst);
    }
    return instances;
}

void Move(std::vector<Instance>& instances, uint32_t frame, float amount) {
    for (size_t i = 0; i < instances.size(); ++i) {
        // Each instance wanders its own way; neighbours drift apart.
        const float phase = 0.37f * float(i) + 0.1f * float(frame);
        instances[i].inverseAndPosition.row[0].w += amount * std::sin(phase);
        instances[i].inverseAndPosition.row[2].w += amount * std::cos(1.3f * phase);
    }
}

void ExpectBoundsNested(const Lbvh& tree) {
    for (size_t p = 0; p < tree.nodes.size(); ++p) {
        if (p == 1 || tree.nodes[p].IsLeaf()) continue;
        const BvhNode& n = tree.nodes[p];
        ASSERT_TRUE(n.Bounds().Contains(tree.nodes[n.leftFirst].Bounds()));
        ASSERT_TRUE(n.Bounds().Contains(tree.nodes[n.leftFirst + 1].Bounds()));
    }
}

const Aabb kUnitBox{vec3(-0.5f), vec3(0.5f)};

TEST(DynamicTlas, AlwaysRebuildModeRebuildsEveryFrame) {
    std::vector<Instance> instances = Grid(4, 1.5f);
    DynamicTlas tlas(TlasPolicy::AlwaysRebuild());
    for (int frame = 0; frame < 3; ++frame)
        EXPECT_TRUE(tlas.Update(instances, std::span(&kUnitBox, 1), false).rebuilt);
}

// A scene with no instance yet (its bodies spawn later): the empty tree costs nothing, frame after
// frame (its SAH cost recursed into the empty root, its own child, until the stack ran out).
TEST(DynamicTlas, EmptySceneCostsNothing) {
    DynamicTlas tlas(TlasPolicy::RefitWhileGood());
    for (int frame = 0; frame < 3; ++frame) {
        const TlasUpdateStats stats = tlas.Update({}, std::span(&kUnitBox, 1), frame == 0);
        EXPECT_EQ(stats.sahCost, 0.0f);
    }
    EXPECT_EQ(ComputeStats(BuildLbvh({}, LbvhLeaves::kPrimitiveIds).nodes).nodeCount, 0u);
}

TEST(DynamicTlas, RefitsWhileQualityHoldsThenRebuilds) {
    std::vector<Instance> instances = Grid(8, 1.5f);
    DynamicTlas tlas(TlasPolicy::RefitWhileGood());
    EXPECT_TRUE(tlas.Update(instances, std::span(&kUnitBox, 1), false).rebuilt);
    // Small motion: refit, quality within the threshold.
    Move(instances, 1, 0.01f);
    TlasUpdateStats stats = tlas.Update(instances, std::span(&kUnitBox, 1), false);
    EXPECT_FALSE(stats.rebuilt);
    EXPECT_LE(stats.sahCost, 1.25f * stats.rebuiltSahCost);
    ExpectBoundsNested(tlas.Tree());
    // Large motion over many frames: refit boxes overlap more and more, so a rebuild comes.
    bool rebuilt = false;
    for (uint32_t frame = 2; frame < 200 && !rebuilt; ++frame) {
        Move(instances, frame, 0.5f);
        stats = tlas.Update(instances, std::span(&kUnitBox, 1), false);
        ExpectBoundsNested(tlas.Tree());
        rebuilt = stats.rebuilt;
        if (!rebuilt) {
            EXPECT_LE(stats.sahCost, 1.25f * stats.rebuiltSahCost);
        }
    }
    EXPECT_TRUE(rebuilt);
}

TEST(DynamicTlas, TopologyChangeForcesARebuild) {
    std::vector<Instance> instances = Grid(3, 1.5f);
    DynamicTlas tlas(TlasPolicy::RefitWhileGood());
    tlas.Update(instances, std::span(&kUnitBox, 1), false);
    EXPECT_FALSE(tlas.Update(instances, std::span(&kUnitBox, 1), false).rebuilt);
    instances.pop_back();
    EXPECT_TRUE(tlas.Update(instances, std::span(&kUnitBox, 1), true).rebuilt);
    EXPECT_EQ(tlas.Tree().primOrder.size(), instances.size());
}

// A policy rebuilds on every update up to its rebuildChangedUpTo instances and refits above: 64
// instances against thresholds of 64 and 63.
TEST(DynamicTlas, RebuildsUpdatesUpToThePolicysSizeAndRefitsAbove) {
    std::vector<Instance> instances = Grid(4, 1.5f);
    ASSERT_EQ(instances.size(), 64u);
    EXPECT_GE(TlasPolicy{}.rebuildChangedUpTo, 1024u);
    TlasPolicy small;
    small.rebuildChangedUpTo = 64;
    TlasPolicy large = small;
    large.rebuildChangedUpTo = 63;
    DynamicTlas rebuilding(small), refitting(large);
    EXPECT_TRUE(rebuilding.Update(instances, std::span(&kUnitBox, 1), false).rebuilt);
    EXPECT_TRUE(refitting.Update(instances, std::span(&kUnitBox, 1), false).rebuilt);
    for (uint32_t frame = 1; frame < 4; ++frame) {
        Move(instances, frame, 0.01f);
        EXPECT_TRUE(rebuilding.Update(instances, std::span(&kUnitBox, 1), false).rebuilt);
        EXPECT_FALSE(refitting.Update(instances, std::span(&kUnitBox, 1), false).rebuilt);
        // The same boxes either way: the root bounds every moved instance.
        const Aabb a = rebuilding.Tree().nodes[0].Bounds(), b = refitting.Tree().nodes[0].Bounds();
        EXPECT_TRUE(a.min == b.min && a.max == b.max);
        ExpectBoundsNested(rebuilding.Tree());
    }
}

// The runtime's policy rebuilds a moved scene at any size: a grid of 22^3 = 10,648 instances,
// above the 4,096 of the policy before, is built afresh on each update that moved it.
TEST(DynamicTlas, DefaultPolicyRebuildsALargeMovedScene) {
    std::vector<Instance> instances = Grid(22, 1.5f);
    ASSERT_EQ(instances.size(), 10648u);
    DynamicTlas tlas;
    EXPECT_TRUE(tlas.Update(instances, std::span(&kUnitBox, 1), false).rebuilt);
    for (uint32_t frame = 1; frame < 3; ++frame) {
        Move(instances, frame, 0.01f);
        EXPECT_TRUE(tlas.Update(instances, std::span(&kUnitBox, 1), false).rebuilt);
        ExpectBoundsNested(tlas.Tree());
    }
}

}  // namespace
}  // namespace rtrt
