// BVH traversal against brute force: on at least 100,000 rays per mesh, the same hit or miss,
// the same primitive and the same t (bit for bit: both use the same intersection test).
#include <gtest/gtest.h>

#include <random>

#include "engine/bvh/blas/blas.h"
#include "tests/bvh/tree_checks.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

using test::ExpectMatchesBruteForce;
using test::Intersect;
using test::Occluded;

class TraversalTest : public test::EveryBuilder {};

TEST_P(TraversalTest, RandomTriangleSoupMatchesBruteForce) {
    ExpectMatchesBruteForce(BuildTriangleBlas(test::RandomTriangles(3000, 7), Options()), 11);
}

TEST_P(TraversalTest, GridWithSharedEdgesMatchesBruteForce) {
    ExpectMatchesBruteForce(BuildTriangleBlas(test::GridMesh(40), Options()), 12);
}

TEST_P(TraversalTest, SpheresMatchBruteForce) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> pos(-5.0f, 5.0f), radius(0.01f, 0.6f);
    std::vector<Sphere> spheres;
    for (int i = 0; i < 2000; ++i)
        spheres.push_back({vec3(pos(rng), pos(rng), pos(rng)), radius(rng)});
    ExpectMatchesBruteForce(BuildSphereBlas(spheres, Options()), 13);
}

INSTANTIATE_TEST_SUITE_P(Builders, TraversalTest, test::kAllBuilders, test::BuilderTestName);

TEST(Traversal, RefitKeepsResultsAfterTheMeshMoves) {
    TriangleMesh mesh = test::RandomTriangles(2000, 3);
    Blas blas = BuildTriangleBlas(mesh);
    // Move every vertex (a shear and a shift); the topology stays, the bounds follow.
    std::vector<Aabb> slotBounds(blas.PrimCount());
    for (uint32_t slot = 0; slot < blas.PrimCount(); ++slot) {
        Triangle& t = blas.triangles[slot];
        for (vec3* v : {&t.v0, &t.v1, &t.v2})
            *v = vec3(v->x + 0.5f * v->y, v->y, v->z) + vec3(3, 0, 0);
        slotBounds[slot] = t.Bounds();
    }
    Refit(blas.nodes, slotBounds);
    blas.nodes4 = CollapseToBvh4(blas.nodes);
    blas.bounds = blas.nodes[0].Bounds();
    ExpectMatchesBruteForce(blas, 21);
}

TEST(Traversal, EmptyBvhHitsNothing) {
    const Blas blas = BuildSphereBlas({});
    Ray ray{vec3(0), kInfinity, vec3(0, 0, 1), 0};
    const RaySetup r = MakeRaySetup(ray);
    EXPECT_FALSE(Intersect(blas, r, kInfinity).hit);
    EXPECT_FALSE(Occluded(blas, r, kInfinity));
}

}  // namespace
}  // namespace rtrt
