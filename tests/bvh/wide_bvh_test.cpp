// The compressed 8-wide BVH (wide_bvh.h): its structure (every primitive in exactly one leaf
// record, every decoded box around everything below it) and its traversal against brute force on
// trees whose quantisation is hard: far from the origin, flat, tiny, one primitive.
#include "engine/bvh/layout/wide_bvh.h"

#include <gtest/gtest.h>

#include <vector>

#include "engine/bvh/blas/blas.h"
#include "tests/bvh/tree_checks.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

Aabb DecodedBox(const WideBvhNode& n, int slot) {
    Aabb b;
    for (int a = 0; a < 3; ++a) {
        const float scale = WideScale(n.exponent[a]);
        b.min[a] = WidePlane(n.origin[a], scale, n.qlo[a][slot]);
        b.max[a] = WidePlane(n.origin[a], scale, n.qhi[a][slot]);
    }
    return b;
}

class WideChecker {
  public:
    WideChecker(const Blas& blas, const WideBvh& wide) : blas_(blas), wide_(wide) {
        seen_.assign(blas.PrimCount(), 0);
    }

    // The bounds of the primitives below node `index`, checking each child's decoded box.
    Aabb Check(uint32_t index, int depth) {
        EXPECT_LT(depth, int(kBvhStackSize)) << "deeper than the traversal's stack";
        const WideBvhNode& n = wide_.nodes.at(index);
        EXPECT_EQ(n.interiorMask & n.leafMask, 0) << "node " << index;
        Aabb all;
        uint32_t interior = 0, leaf = 0;
        for (int s = 0; s < kWideArity; ++s) {
            Aabb below;
            if ((n.leafMask >> s) & 1) {
                const WideBvhLeaf& l = wide_.leaves.at(n.leafBase + leaf++);
                for (uint32_t i = 0; i < l.count; ++i) {
                    const uint32_t slot = l.first + i;
                    EXPECT_LT(slot, blas_.PrimCount());
                    if (slot >= blas_.PrimCount()) continue;
                    ++seen_[slot];
                    below.Grow(blas_.kind == GeometryKind::kTriangles
                                   ? blas_.triangles[slot].Bounds()
                                   : blas_.spheres[slot].Bounds());
                }
            } else if ((n.interiorMask >> s) & 1) {
                below = Check(n.childBase + interior++, depth + 1);
            } else {
                continue;
            }
            EXPECT_TRUE(DecodedBox(n, s).Contains(below))
                << "node " << index << " slot " << s << " does not enclose its contents";
            all.Grow(below);
        }
        return all;
    }

    void ExpectEveryPrimitiveOnce() const {
        for (uint32_t slot = 0; slot < seen_.size(); ++slot)
            EXPECT_EQ(seen_[slot], 1u) << "slot " << slot;
    }

  private:
    const Blas& blas_;
    const WideBvh& wide_;
    std::vector<uint32_t> seen_;
};

void ExpectSound(const Blas& blas) {
    const WideBvh wide = CollapseToWideBvh(blas.nodes);
    ASSERT_FALSE(wide.nodes.empty());
    WideChecker checker(blas, wide);
    checker.Check(0, 0);
    checker.ExpectEveryPrimitiveOnce();
}

TriangleMesh Moved(TriangleMesh mesh, vec3 scale, vec3 offset) {
    for (vec3& p : mesh.positions) p = p * scale + offset;
    return mesh;
}

TEST(WideBvh, RandomSoupIsSoundAndMatchesBruteForce) {
    const Blas blas = BuildTriangleBlas(test::RandomTriangles(2000, 3));
    ExpectSound(blas);
    test::ExpectMatchesBruteForce(blas, 31);
}

TEST(WideBvh, TinyModelFarFromTheOriginIsSound) {
    // Extents of 0.5 at 1e4: a quantisation step (about 0.002) is two of the origin's float
    // spacings, so the planes' rounding decides the boxes.
    const Blas blas = BuildTriangleBlas(
        Moved(test::RandomTriangles(2000, 4), vec3(0.25f), vec3(1e4f, -1.2e4f, 9e3f)));
    ExpectSound(blas);
    test::ExpectMatchesBruteForce(blas, 32);
}

TEST(WideBvh, FlatGridIsSound) {
    // Every box has zero extent along one axis.
    const Blas blas = BuildTriangleBlas(test::GridMesh(30));
    ExpectSound(blas);
    test::ExpectMatchesBruteForce(blas, 33);
}

TEST(WideBvh, HugeSpreadIsSound) {
    const Blas blas = BuildTriangleBlas(Moved(test::RandomTriangles(3000, 5), vec3(1e30f), {}));
    ExpectSound(blas);
}

TEST(WideBvh, SpheresAreSound) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> pos(-5.0f, 5.0f), radius(0.01f, 0.6f);
    std::vector<Sphere> spheres;
    for (int i = 0; i < 1500; ++i)
        spheres.push_back({vec3(pos(rng), pos(rng), pos(rng)), radius(rng)});
    ExpectSound(BuildSphereBlas(spheres));
}

TEST(WideBvh, OneTriangleIsARootWithOneLeaf) {
    const Blas blas = BuildTriangleBlas(test::RandomTriangles(1, 6));
    const WideBvh wide = CollapseToWideBvh(blas.nodes);
    ASSERT_EQ(wide.nodes.size(), 1u);
    EXPECT_EQ(wide.nodes[0].interiorMask, 0);
    EXPECT_EQ(__builtin_popcount(wide.nodes[0].leafMask), 1);
    ASSERT_EQ(wide.leaves.size(), 1u);
    EXPECT_EQ(wide.leaves[0].first, 0u);
    EXPECT_EQ(wide.leaves[0].count, 1u);
}

TEST(WideBvh, EmptyTreeHitsNothing) {
    const Blas blas = BuildSphereBlas({});
    const WideBvh wide = CollapseToWideBvh(blas.nodes);
    ASSERT_EQ(wide.nodes.size(), 1u);
    EXPECT_EQ(wide.nodes[0].interiorMask | wide.nodes[0].leafMask, 0);
    const RaySetup r = MakeRaySetup(Ray{vec3(0), kInfinity, vec3(0, 0, 1), 0});
    EXPECT_FALSE(test::IntersectWide8(blas, wide, r, kInfinity).hit);
    EXPECT_FALSE(test::OccludedWide8(blas, wide, r, kInfinity));
}

TEST(WideBvh, NonFiniteBoxesStayBinary) {
    Blas blas = BuildTriangleBlas(test::RandomTriangles(100, 7));
    for (BvhNode& node : blas.nodes) node.boundsMax.x = kInfinity;
    EXPECT_TRUE(CollapseToWideBvh(blas.nodes).nodes.empty());
}

TEST(WideBvh, WideNodesHoldUpToEightChildren) {
    const Blas blas = BuildTriangleBlas(test::RandomTriangles(20000, 8));
    const WideBvh wide = CollapseToWideBvh(blas.nodes);
    uint32_t children = 0;
    for (const WideBvhNode& n : wide.nodes)
        children += __builtin_popcount(n.interiorMask | n.leafMask);
    // Interior children are opened until a node has eight or only leaves: most nodes are full
    // but those just above the leaves.
    EXPECT_GT(double(children) / double(wide.nodes.size()), 4.0);
}

}  // namespace
}  // namespace rtrt
