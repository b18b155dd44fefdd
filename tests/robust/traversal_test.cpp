// Traversal against brute force and bad rays on the CPU (traversal_checks.h). 2,000,000 rays: the
// CPU back end's 4-wide BLAS traversal and the binary one are both compared.
#include "engine/bvh/traversal/traversal.h"

#include "tests/robust/cpu_runner.h"
#include "tests/robust/traversal_checks.h"

namespace rtrt::robust {
namespace {

TEST(TraversalVsBruteForce, TwoMillionRandomAndEdgeAimedRays) {
    CheckTraversalMatchesBruteForce(CpuRunner{}, 2'000'000);
}

TEST(TraversalVsBruteForce, NanAndInfiniteRaysHitNothingAndReturn) { CheckBadRays(CpuRunner{}); }

// Below IsTraceable: a BLAS traversal handed a NaN ray directly still ends, having visited each
// node at most once (NaN slab lanes are dropped, so every box may pass; the stack bounds the walk).
TEST(TraversalVsBruteForce, NanRayBelowTheTraceableGateStillTerminates) {
    const Blas blas = BuildTriangleBlas(UvSphere(32, 16, 1.0f, vec3(0)).mesh);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const Ray& ray : {Ray{vec3(0, 0, 5), kInfinity, vec3(nan, 0, -1), 0},
                           Ray{vec3(nan), kInfinity, vec3(0, 0, -1), 0},
                           Ray{vec3(0, 0, 5), kInfinity, vec3(nan), 0}}) {
        TraversalStats stats;
        float tMax = ray.tMax;
        const bool hit = Traverse<Query::kIntersect>(
            blas.nodes.data(), MakeRaySetup(ray), tMax,
            [&](uint32_t slot, float& tBest) {
                TriangleHit h;
                return IntersectTriangle(blas.triangles[slot], MakeRaySetup(ray), tBest, &h);
            },
            &stats);
        EXPECT_FALSE(hit);
        EXPECT_LE(stats.nodesVisited, blas.nodes.size());
    }
}

}  // namespace
}  // namespace rtrt::robust
