// The spatial-split builder (SBVH): its trees are well formed, hold every triangle within the
// reference budget, cost less than binned SAH where large triangles cross small ones, equal the
// binned tree without a budget, and are the same on any number of threads. Its traversal against
// brute force runs with every builder in bvh_traversal_test.cpp and model_bvh_test.cpp.
#include "engine/bvh/build/spatial_split_builder.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <random>
#include <set>

#include "engine/bvh/blas/blas.h"
#include "engine/bvh/blas/blas_check.h"
#include "engine/core/error.h"
#include "tests/bvh/tree_checks.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

BvhBuildOptions Spatial(float budget = 0.25f) {
    BvhBuildOptions o;
    o.builder = BvhBuilder::kSpatialSah;
    o.spatialSplitBudget = budget;
    return o;
}

// Long thin triangles across a cube, each from near one face to near the opposite one: their
// boxes overlap whatever object split is taken, so the builder splits many of them.
TriangleMesh Slivers(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), w(0.001f, 0.01f);
    TriangleMesh mesh;
    for (uint32_t i = 0; i < count; ++i) {
        const int axis = int(i % 3);
        vec3 a(u(rng), u(rng), u(rng)), b = a;
        a[axis] = -1.0f;
        b[axis] = 1.0f;
        vec3 c = 0.5f * (a + b);
        c[(axis + 1) % 3] += w(rng);
        const uint32_t v = uint32_t(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), {a, b, c});
        mesh.indices.push_back({v, v + 1, v + 2});
    }
    return mesh;
}

Triangle SourceTriangle(const TriangleMesh& mesh, uint32_t i) {
    const glm::uvec3 idx = mesh.indices[i];
    return {mesh.positions[idx.x], mesh.positions[idx.y], mesh.positions[idx.z]};
}

bool Overlap(const Aabb& a, const Aabb& b) {
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
           a.min.z <= b.max.z && b.min.z <= a.max.z;
}

TEST(SpatialSplitBuilder, EveryTriangleIsInALeafWithinTheBudget) {
    const TriangleMesh mesh = Slivers(3000, 1);
    const Blas blas = BuildTriangleBlas(mesh, Spatial(0.25f));
    const uint32_t n = uint32_t(mesh.indices.size());
    EXPECT_GT(blas.PrimCount(), n) << "no triangle was split: the test proves nothing";
    EXPECT_LE(blas.PrimCount(), n + n / 4);
    EXPECT_NO_THROW(CheckBlas(blas, "sbvh", true));
    EXPECT_LT(ComputeStats(blas.nodes).maxDepth, kBvhStackSize);

    std::vector<uint32_t> leavesOf(n, 0);
    std::vector<uint32_t> stack{0};
    while (!stack.empty()) {
        const BvhNode& node = blas.nodes[stack.back()];
        stack.pop_back();
        if (!node.IsLeaf()) {
            ASSERT_EQ(node.leftFirst % 2, 0u);
            EXPECT_TRUE(node.Bounds().Contains(blas.nodes[node.leftFirst].Bounds()));
            EXPECT_TRUE(node.Bounds().Contains(blas.nodes[node.leftFirst + 1].Bounds()));
            stack.push_back(node.leftFirst);
            stack.push_back(node.leftFirst + 1);
            continue;
        }
        for (uint32_t slot = node.leftFirst; slot < node.leftFirst + node.primCount; ++slot) {
            const uint32_t id = blas.primIds[slot];
            ASSERT_LT(id, n);
            ++leavesOf[id];
            const Triangle& t = blas.triangles[slot];
            const Triangle source = SourceTriangle(mesh, id);
            EXPECT_EQ(t.v0, source.v0);
            EXPECT_EQ(t.v1, source.v1);
            EXPECT_EQ(t.v2, source.v2);
            // A reference's box is a part of its triangle's box, never beside it.
            EXPECT_TRUE(Overlap(node.Bounds(), t.Bounds()));
        }
    }
    uint32_t listed = 0;
    for (uint32_t k : leavesOf) {
        EXPECT_GE(k, 1u);
        listed += k;
    }
    EXPECT_EQ(listed, blas.PrimCount());
}

// A few large triangles across a soup of small ones (a floor or a wall among props): binned SAH
// must keep each large triangle whole, so its box overlaps every node it passes; spatial splits
// cut it into parts each bounding only its own node's share.
// Many references split, so rays aimed at the triangles cross many split planes: closest hit,
// any hit, binary and 4-wide layout all as brute force finds them.
TEST(SpatialSplitBuilder, SplitSliversTraceAsBruteForce) {
    const Blas blas = BuildTriangleBlas(Slivers(3000, 8), Spatial(1.0f));
    ASSERT_GT(blas.PrimCount(), 3300u) << "too few triangles were split to test their parts";
    test::ExpectMatchesBruteForce(blas, 21);
}

TEST(SpatialSplitBuilder, CostsLessThanBinnedSahWhereLargeTrianglesCrossSmallOnes) {
    TriangleMesh mesh = test::RandomTriangles(4000, 9);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 16; ++i) {
        const uint32_t v = uint32_t(mesh.positions.size());
        for (int k = 0; k < 3; ++k) mesh.positions.push_back(vec3(u(rng), u(rng), u(rng)));
        mesh.indices.push_back({v, v + 1, v + 2});
    }
    const float binned = SahCost(BuildTriangleBlas(mesh).nodes);
    const float spatial = SahCost(BuildTriangleBlas(mesh, Spatial(0.25f)).nodes);
    const float generous = SahCost(BuildTriangleBlas(mesh, Spatial(1.0f)).nodes);
    EXPECT_LT(spatial, 0.92f * binned) << "binned " << binned << ", sbvh " << spatial;
    EXPECT_LT(generous, spatial);
}

// Without a budget no reference is split, and what is left is the binned SAH search over the same
// boxes: the same nodes bit for bit, and each leaf the same triangles.
TEST(SpatialSplitBuilder, WithoutABudgetItBuildsTheBinnedTree) {
    const TriangleMesh mesh = test::RandomTriangles(20000, 3);
    const Blas binned = BuildTriangleBlas(mesh);
    const Blas spatial = BuildTriangleBlas(mesh, Spatial(0.0f));
    ASSERT_EQ(binned.nodes.size(), spatial.nodes.size());
    ASSERT_EQ(binned.PrimCount(), spatial.PrimCount());
    for (size_t i = 0; i < binned.nodes.size(); ++i) {
        const BvhNode &a = binned.nodes[i], &b = spatial.nodes[i];
        ASSERT_EQ(a.boundsMin, b.boundsMin) << "node " << i;
        ASSERT_EQ(a.boundsMax, b.boundsMax) << "node " << i;
        ASSERT_EQ(a.leftFirst, b.leftFirst) << "node " << i;
        ASSERT_EQ(a.primCount, b.primCount) << "node " << i;
        if (!a.IsLeaf() || i == 1) continue;
        const std::set<uint32_t> x(binned.primIds.begin() + a.leftFirst,
                                   binned.primIds.begin() + a.leftFirst + a.primCount);
        const std::set<uint32_t> y(spatial.primIds.begin() + b.leftFirst,
                                   spatial.primIds.begin() + b.leftFirst + b.primCount);
        ASSERT_EQ(x, y) << "leaf " << i;
    }
}

TEST(SpatialSplitBuilder, SameTreeOnAnyNumberOfThreads) {
    TriangleMesh mesh = Slivers(6000, 4);
    const TriangleMesh soup = test::RandomTriangles(6000, 5);
    for (const glm::uvec3 idx : soup.indices) {
        const uint32_t v = uint32_t(mesh.positions.size());
        for (int k = 0; k < 3; ++k) mesh.positions.push_back(soup.positions[idx[k]]);
        mesh.indices.push_back({v, v + 1, v + 2});
    }
    auto build = [&](int threads) {
        tbb::task_arena arena(threads);
        Blas blas;
        arena.execute([&] { blas = BuildTriangleBlas(mesh, Spatial()); });
        return blas;
    };
    const Blas one = build(1), four = build(4);
    ASSERT_EQ(one.nodes.size(), four.nodes.size());
    EXPECT_EQ(0,
              std::memcmp(one.nodes.data(), four.nodes.data(), one.nodes.size() * sizeof(BvhNode)));
    EXPECT_EQ(one.primIds, four.primIds);
}

TEST(SpatialSplitBuilder, OnlyASpatialSplitTreeMayListATriangleTwice) {
    const Blas blas = BuildTriangleBlas(Slivers(500, 6), Spatial());
    ASSERT_GT(blas.PrimCount(), 500u);
    EXPECT_NO_THROW(CheckBlas(blas, "m.rtmodel", true));
    // Every triangle must be in some slot: drop all of triangle 0's.
    Blas gap = blas;
    for (uint32_t& id : gap.primIds)
        if (id == 0) id = 1;
    try {
        CheckBlas(gap, "m.rtmodel", true);
        ADD_FAILURE() << "a triangle in no leaf was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("primitive 0 is in no leaf slot"), std::string::npos)
            << e.what();
    }
    try {
        CheckBlas(blas, "m.rtmodel");
        ADD_FAILURE() << "a permutation was expected";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("listed twice"), std::string::npos) << e.what();
    }
}

// The rest mesh of a spatial-split BLAS has each source triangle once, with its own vertices.
TEST(SpatialSplitBuilder, RestMeshHasEachTriangleOnce) {
    const TriangleMesh mesh = Slivers(800, 7);
    const Blas blas = BuildTriangleBlas(mesh, Spatial());
    ASSERT_GT(blas.PrimCount(), 800u);
    const TriangleMesh rest = RestMeshOfBlas(blas).rest;
    ASSERT_EQ(rest.indices.size(), mesh.indices.size());
    for (uint32_t i = 0; i < rest.indices.size(); ++i) {
        const Triangle a = SourceTriangle(rest, i), b = SourceTriangle(mesh, i);
        EXPECT_EQ(a.v0, b.v0);
        EXPECT_EQ(a.v1, b.v1);
        EXPECT_EQ(a.v2, b.v2);
    }
}

}  // namespace
}  // namespace rtrt
