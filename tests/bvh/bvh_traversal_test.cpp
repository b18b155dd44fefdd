// BVH traversal against brute force: on at least 100,000 rays per mesh, the same hit or miss,
// the same primitive and the same t (bit for bit: both use the same intersection test).
#include <gtest/gtest.h>

#include <random>

#include "engine/bvh/blas/blas.h"
#include "engine/bvh/traversal/bvh4_traversal.h"
#include "engine/bvh/traversal/traversal.h"
#include "engine/geometry/sphere_intersect.h"
#include "engine/geometry/triangle_intersect.h"
#include "game/assets/mesh_io.h"
#include "game/assets/teapot.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

constexpr uint32_t kRayCount = 100000;

struct Found {
    bool hit = false;
    float t = kInfinity;
    uint32_t slot = 0;
};

bool HitsAt(const Blas& blas, uint32_t slot, const RaySetup& r, float t) {
    if (blas.kind == GeometryKind::kTriangles) {
        TriangleHit h;
        return IntersectTriangle(blas.triangles[slot], r, kInfinity, &h) && h.t == t;
    }
    float ts;
    return IntersectSphere(blas.spheres[slot], r, t, &ts) && ts == t;
}

Found BruteForce(const Blas& blas, const RaySetup& r, float tMax) {
    Found f;
    for (uint32_t slot = 0; slot < blas.PrimCount(); ++slot) {
        float t;
        bool hit;
        if (blas.kind == GeometryKind::kTriangles) {
            TriangleHit h;
            hit = IntersectTriangle(blas.triangles[slot], r, tMax, &h);
            t = h.t;
        } else {
            hit = IntersectSphere(blas.spheres[slot], r, tMax, &t);
        }
        if (hit && t < f.t) f = {true, t, slot};
    }
    return f;
}

Found Intersect(const Blas& blas, const RaySetup& r, float tMax) {
    Found f;
    f.hit = Traverse<Query::kIntersect>(
        blas.nodes.data(), r, tMax,
        [&](uint32_t slot, float& tBest) {
            float t;
            bool hit;
            if (blas.kind == GeometryKind::kTriangles) {
                TriangleHit h;
                hit = IntersectTriangle(blas.triangles[slot], r, tBest, &h);
                t = h.t;
            } else {
                hit = IntersectSphere(blas.spheres[slot], r, tBest, &t);
            }
            if (!hit) return false;
            tBest = f.t = t;
            f.slot = slot;
            return true;
        },
        nullptr);
    return f;
}

// The CPU's 4-wide traversal of the same BLAS (triangles only).
Found Intersect4(const Blas& blas, const RaySetup& r, float tMax) {
    Found f;
    f.hit =
        Traverse4<Query::kIntersect>(blas.nodes4.data(), r, tMax, [&](uint32_t slot, float& tBest) {
            TriangleHit h;
            if (!IntersectTriangle(blas.triangles[slot], r, tBest, &h)) return false;
            tBest = f.t = h.t;
            f.slot = slot;
            return true;
        });
    return f;
}

bool Occluded4(const Blas& blas, const RaySetup& r, float tMax) {
    return Traverse4<Query::kOccluded>(
        blas.nodes4.data(), r, tMax, [&](uint32_t slot, float tLimit) {
            TriangleHit h;
            return IntersectTriangle(blas.triangles[slot], r, tLimit, &h);
        });
}

bool Occluded(const Blas& blas, const RaySetup& r, float tMax) {
    return Traverse<Query::kOccluded>(
        blas.nodes.data(), r, tMax,
        [&](uint32_t slot, float tLimit) {
            if (blas.kind == GeometryKind::kTriangles) {
                TriangleHit h;
                return IntersectTriangle(blas.triangles[slot], r, tLimit, &h);
            }
            float t;
            return IntersectSphere(blas.spheres[slot], r, tLimit, &t);
        },
        nullptr);
}

// Half the rays start anywhere around the model in random directions; half are aimed at a random
// point of a random primitive, so most of them hit.
Ray RandomRay(const Blas& blas, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const Aabb b = blas.bounds;
    const vec3 margin(0.5f * MaxComponent(b.Extent()));  // flat meshes too
    const vec3 lo = b.min - margin, hi = b.max + margin;
    Ray ray;
    ray.origin = lo + vec3(u(rng), u(rng), u(rng)) * (hi - lo);
    ray.tMax = kInfinity;
    ray.pad = 0;
    if (u(rng) < 0.5f) {
        ray.dir = glm::normalize(vec3(u(rng), u(rng), u(rng)) - vec3(0.5f));
    } else {
        const uint32_t slot = std::min(blas.PrimCount() - 1, uint32_t(u(rng) * blas.PrimCount()));
        vec3 target;
        if (blas.kind == GeometryKind::kTriangles) {
            float a = u(rng), c = u(rng);
            if (a + c > 1) a = 1 - a, c = 1 - c;
            const Triangle& t = blas.triangles[slot];
            target = t.v0 + a * (t.v1 - t.v0) + c * (t.v2 - t.v0);
        } else {
            target = blas.spheres[slot].center;
        }
        ray.dir = target - ray.origin;
    }
    return ray;
}

void ExpectMatchesBruteForce(const Blas& blas, uint32_t seed) {
    std::mt19937 rng(seed);
    uint32_t hits = 0, mismatches = 0;
    for (uint32_t i = 0; i < kRayCount; ++i) {
        const Ray ray = RandomRay(blas, rng);
        const RaySetup r = MakeRaySetup(ray);
        const Found expected = BruteForce(blas, r, ray.tMax);
        const Found got = Intersect(blas, r, ray.tMax);
        hits += expected.hit;
        bool same = expected.hit == got.hit;
        if (same && expected.hit) {
            // Equal t on two primitives (a shared edge) is a tie: either is the closest hit.
            same = expected.t == got.t &&
                   (expected.slot == got.slot || HitsAt(blas, got.slot, r, got.t));
        }
        if (!same && ++mismatches <= 5) {
            ADD_FAILURE() << "ray " << i << ": brute force " << expected.hit << " t=" << expected.t
                          << " slot=" << expected.slot << ", BVH " << got.hit << " t=" << got.t
                          << " slot=" << got.slot;
        }
        // The occlusion query with tMax just past the closest hit agrees with the closest hit.
        const float tLimit = expected.hit ? expected.t * 1.001f : 1e30f;
        if (Occluded(blas, r, tLimit) != expected.hit && ++mismatches <= 5)
            ADD_FAILURE() << "ray " << i << ": the occlusion query disagrees with brute force";
        if (blas.nodes4.empty()) continue;
        const Found wide = Intersect4(blas, r, ray.tMax);
        const bool wideSame =
            wide.hit == expected.hit &&
            (!wide.hit || (wide.t == expected.t &&
                           (wide.slot == expected.slot || HitsAt(blas, wide.slot, r, wide.t))));
        if (!wideSame && ++mismatches <= 5)
            ADD_FAILURE() << "ray " << i << ": 4-wide BVH " << wide.hit << " t=" << wide.t
                          << ", brute force " << expected.hit << " t=" << expected.t;
        if (Occluded4(blas, r, tLimit) != expected.hit && ++mismatches <= 5)
            ADD_FAILURE() << "ray " << i
                          << ": the 4-wide occlusion query disagrees with brute force";
    }
    EXPECT_EQ(mismatches, 0u);
    EXPECT_GT(hits, kRayCount / 4) << "too few hits for the comparison to mean much";
}

class TraversalTest : public ::testing::TestWithParam<BvhBuilder> {
  protected:
    BvhBuildOptions Options() const {
        BvhBuildOptions o;
        o.builder = GetParam();
        return o;
    }
};

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

TEST_P(TraversalTest, DragonRes4MatchesBruteForce) {
    RTRT_REQUIRE_MODEL(path, "dragon_vrip_res4.ply.gz");
    ExpectMatchesBruteForce(BuildTriangleBlas(LoadMesh(path), Options()), 14);
}

TEST_P(TraversalTest, TeapotMatchesBruteForce) {
    RTRT_REQUIRE_MODEL(path, "teapot.inc");
    ExpectMatchesBruteForce(BuildTriangleBlas(TessellateTeapot(path, 6), Options()), 15);
}

INSTANTIATE_TEST_SUITE_P(Builders, TraversalTest,
                         ::testing::Values(BvhBuilder::kBinnedSah, BvhBuilder::kSweepSah,
                                           BvhBuilder::kCentroidSplit),
                         [](const auto& info) { return std::string(BuilderName(info.param)); });

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
