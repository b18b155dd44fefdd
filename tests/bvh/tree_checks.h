#pragma once
// Checks of BVHs, for the suites that check trees (bvh's own, and the real
// models' in tests/assets): the same hit or miss, the same primitive and the same t (bit for bit:
// both use the same intersection test), for the binary and the 4-wide layout and both queries;
// and the structure of a tree.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "engine/bvh/blas/blas.h"
#include "engine/bvh/traversal/bvh4_traversal.h"
#include "engine/bvh/traversal/traversal.h"
#include "engine/geometry/sphere_intersect.h"
#include "engine/geometry/triangle_intersect.h"

namespace rtrt::test {

inline constexpr uint32_t kRayCount = 100000;

struct Found {
    bool hit = false;
    float t = kInfinity;
    uint32_t slot = 0;
};

inline bool HitsAt(const Blas& blas, uint32_t slot, const RaySetup& r, float t) {
    if (blas.kind == GeometryKind::kTriangles) {
        TriangleHit h;
        return IntersectTriangle(blas.triangles[slot], r, kInfinity, &h) && h.t == t;
    }
    float ts;
    return IntersectSphere(blas.spheres[slot], r, t, &ts) && ts == t;
}

inline Found BruteForce(const Blas& blas, const RaySetup& r, float tMax) {
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

inline Found Intersect(const Blas& blas, const RaySetup& r, float tMax) {
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
inline Found Intersect4(const Blas& blas, const RaySetup& r, float tMax) {
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

inline bool Occluded4(const Blas& blas, const RaySetup& r, float tMax) {
    return Traverse4<Query::kOccluded>(
        blas.nodes4.data(), r, tMax, [&](uint32_t slot, float tLimit) {
            TriangleHit h;
            return IntersectTriangle(blas.triangles[slot], r, tLimit, &h);
        });
}

inline bool Occluded(const Blas& blas, const RaySetup& r, float tMax) {
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
inline Ray RandomRay(const Blas& blas, std::mt19937& rng) {
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

inline void ExpectMatchesBruteForce(const Blas& blas, uint32_t seed) {
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

// Every node bounds its children (or its primitives), every primitive sits in exactly one leaf,
// pairs start at even indices.
inline void ExpectWellFormed(const Blas& blas) {
    std::vector<uint32_t> seen(blas.PrimCount(), 0);
    std::vector<uint32_t> stack{0};
    while (!stack.empty()) {
        const BvhNode& node = blas.nodes[stack.back()];
        stack.pop_back();
        if (node.IsLeaf()) {
            for (uint32_t i = 0; i < node.primCount; ++i) {
                const uint32_t slot = node.leftFirst + i;
                ASSERT_LT(slot, blas.PrimCount());
                ++seen[slot];
                EXPECT_TRUE(node.Bounds().Contains(blas.triangles[slot].Bounds()));
            }
            continue;
        }
        ASSERT_EQ(node.leftFirst % 2, 0u);
        ASSERT_LT(node.leftFirst + 1, blas.nodes.size());
        EXPECT_TRUE(node.Bounds().Contains(blas.nodes[node.leftFirst].Bounds()));
        EXPECT_TRUE(node.Bounds().Contains(blas.nodes[node.leftFirst + 1].Bounds()));
        stack.push_back(node.leftFirst);
        stack.push_back(node.leftFirst + 1);
    }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](uint32_t n) { return n == 1; }));
    std::vector<uint32_t> ids = blas.primIds;
    std::sort(ids.begin(), ids.end());
    std::vector<uint32_t> expected(ids.size());
    std::iota(expected.begin(), expected.end(), 0u);
    EXPECT_EQ(ids, expected);
}

// A test over every BVH builder: TEST_P suites derive from it and instantiate with kAllBuilders.
class EveryBuilder : public ::testing::TestWithParam<BvhBuilder> {
  protected:
    BvhBuildOptions Options() const {
        BvhBuildOptions o;
        o.builder = GetParam();
        return o;
    }
};
inline const auto kAllBuilders =
    ::testing::Values(BvhBuilder::kBinnedSah, BvhBuilder::kSweepSah, BvhBuilder::kCentroidSplit,
                      BvhBuilder::kSpatialSah);
inline std::string BuilderTestName(const ::testing::TestParamInfo<BvhBuilder>& info) {
    return std::string(BuilderName(info.param));
}

}  // namespace rtrt::test
