#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "engine/bvh/blas/blas.h"
#include "tests/bvh/tree_checks.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

using test::ExpectWellFormed;

TEST(BvhBuilder, EveryBuilderMakesAWellFormedTree) {
    const TriangleMesh mesh = test::RandomTriangles(5000, 1);
    for (BvhBuilder b :
         {BvhBuilder::kBinnedSah, BvhBuilder::kSweepSah, BvhBuilder::kCentroidSplit}) {
        SCOPED_TRACE(std::string(BuilderName(b)));
        BvhBuildOptions o;
        o.builder = b;
        ExpectWellFormed(BuildTriangleBlas(mesh, o));
    }
}

TEST(BvhBuilder, TrianglesAreStoredInLeafOrder) {
    const TriangleMesh mesh = test::RandomTriangles(500, 2);
    const Blas blas = BuildTriangleBlas(mesh);
    for (uint32_t slot = 0; slot < blas.PrimCount(); ++slot) {
        const glm::uvec3 idx = mesh.indices[blas.primIds[slot]];
        EXPECT_EQ(blas.triangles[slot].v0, mesh.positions[idx.x]);
        EXPECT_EQ(blas.triangles[slot].v2, mesh.positions[idx.z]);
    }
}

// The full sweep searches a superset of the binned planes: its tree is never much worse; both
// beat the paper's centroid split.
TEST(BvhBuilder, SahBuildersBeatTheCentroidSplit) {
    const TriangleMesh mesh = test::RandomTriangles(20000, 3);
    auto cost = [&](BvhBuilder b) {
        BvhBuildOptions o;
        o.builder = b;
        return SahCost(BuildTriangleBlas(mesh, o).nodes);
    };
    const float binned = cost(BvhBuilder::kBinnedSah);
    const float sweep = cost(BvhBuilder::kSweepSah);
    const float centroid = cost(BvhBuilder::kCentroidSplit);
    EXPECT_LE(sweep, binned * 1.02f);
    EXPECT_LT(binned, centroid);
    EXPECT_GT(binned, 1.0f);
}

TEST(BvhBuilder, SahCostOfASingleLeafIsItsPrimitiveCount) {
    const TriangleMesh mesh = test::RandomTriangles(1, 4);
    const Blas blas = BuildTriangleBlas(mesh);
    EXPECT_FLOAT_EQ(SahCost(blas.nodes), 1.0f);
}

// The cost is the sum over every node of its area relative to the root's (times its primitive
// count for a leaf), summed in double: in float, a few hundred thousand terms lose the third digit.
TEST(BvhBuilder, SahCostIsTheSumOverEveryNode) {
    const Blas blas = BuildTriangleBlas(test::RandomTriangles(200000, 6));
    const double rootArea = blas.nodes[0].Bounds().Area();
    double expected = 0.0;
    std::vector<uint32_t> stack = {0};
    while (!stack.empty()) {
        const BvhNode& node = blas.nodes[stack.back()];
        stack.pop_back();
        const double relArea = node.Bounds().Area() / rootArea;
        if (node.IsLeaf()) {
            expected += node.primCount * relArea;
        } else {
            expected += relArea;
            stack.insert(stack.end(), {node.leftFirst, node.leftFirst + 1});
        }
    }
    EXPECT_NEAR(SahCost(blas.nodes), expected, 1e-6 * expected);
}

TEST(BvhBuilder, IdenticalPrimitivesStillSplitIntoBoundedLeaves) {
    // 1000 copies of one triangle: no plane separates their centroids.
    TriangleMesh mesh;
    mesh.positions = {vec3(0), vec3(1, 0, 0), vec3(0, 1, 0)};
    mesh.indices.assign(1000, glm::uvec3(0, 1, 2));
    const Blas blas = BuildTriangleBlas(mesh);
    ExpectWellFormed(blas);
    EXPECT_LE(ComputeStats(blas.nodes).maxLeafSize, 8u);
}

TEST(BvhBuilder, NodeArrayBytesAreStated) {
    const Blas blas = BuildTriangleBlas(test::RandomTriangles(100, 5));
    const BvhStats stats = ComputeStats(blas.nodes);
    EXPECT_EQ(stats.bytes, blas.nodes.size() * 32);
    EXPECT_EQ(stats.nodeCount + 1, blas.nodes.size());  // + the unused slot 1
}

TEST(BvhBuilder, ParsesBuilderNames) {
    BvhBuilder b;
    EXPECT_TRUE(ParseBuilder("sweep", &b));
    EXPECT_EQ(b, BvhBuilder::kSweepSah);
    EXPECT_FALSE(ParseBuilder("sah", &b));
}

// The SAH cost of a model whose boxes' areas overflow a float had been NaN (rtrt info, convert).
TEST(BvhBuilder, AHugeModelsSahCostIsFinite) {
    auto triangle = [](float edge) {
        TriangleMesh mesh;
        mesh.positions = {vec3(0.0f), vec3(edge, 0.0f, 0.0f), vec3(0.0f, edge, 0.0f)};
        mesh.indices = {glm::uvec3(0, 1, 2)};
        return BuildTriangleBlas(mesh);
    };
    const float cost = ComputeStats(triangle(1e20f).nodes).sahCost;
    EXPECT_TRUE(std::isfinite(cost)) << cost;
    EXPECT_EQ(cost, ComputeStats(triangle(1.0f).nodes).sahCost);
}

}  // namespace
}  // namespace rtrt
