// The CPU's four-triangle test (triangle_intersect4.h) against the scalar watertight test, lane
// by lane and bit for bit: the same hits, t and barycentrics, on random triangles and rays at
// many scales, on rays through shared edges and vertices (edge functions exactly 0), on rays that
// start on a triangle (the plane test's band), on degenerate and non-finite triangles, and the
// leaf helpers' choice among hits at equal t.
#include "engine/geometry/triangle_intersect4.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>
#include <vector>

namespace rtrt {
namespace {

struct Counts {
    uint32_t hits = 0, misses = 0;
};

// Every group of 1-4 triangles of tris (in order) against ray: each lane as the scalar test.
void ExpectLanesMatchScalar(const std::vector<Triangle>& tris, const Ray& ray, Counts* counts) {
    const RaySetup r = MakeRaySetup(ray);
    for (size_t first = 0; first < tris.size(); first += 4) {
        const uint32_t n = uint32_t(std::min<size_t>(4, tris.size() - first));
        TriangleHits4 lanes;
        IntersectTriangles4(&tris[first], n, r, ray.tMax, &lanes);
        EXPECT_EQ(lanes.mask & ~((1 << n) - 1), 0);
        for (uint32_t i = 0; i < n; ++i) {
            TriangleHit h;
            const bool scalar = IntersectTriangle(tris[first + i], r, ray.tMax, &h);
            const bool wide = ((lanes.mask >> i) & 1) != 0;
            ASSERT_EQ(wide, scalar) << "triangle " << first + i;
            if (!scalar) {
                ++counts->misses;
                continue;
            }
            ++counts->hits;
            EXPECT_EQ(std::bit_cast<uint32_t>(lanes.t[i]), std::bit_cast<uint32_t>(h.t));
            EXPECT_EQ(std::bit_cast<uint32_t>(lanes.b1[i]), std::bit_cast<uint32_t>(h.b1));
            EXPECT_EQ(std::bit_cast<uint32_t>(lanes.b2[i]), std::bit_cast<uint32_t>(h.b2));
        }
    }
}

TEST(TriangleIntersect4, RandomTrianglesAndRaysMatchTheScalarTest) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    Counts counts;
    for (int scene = 0; scene < 400; ++scene) {
        const float scale = std::pow(10.0f, float(scene % 9) - 4.0f);  // 1e-4 .. 1e4
        const vec3 offset = vec3(unit(rng), unit(rng), unit(rng)) * (scale * float(scene % 3));
        std::vector<Triangle> tris;
        for (int i = 0; i < 1 + scene % 11; ++i) {
            const vec3 c = offset + vec3(unit(rng), unit(rng), unit(rng)) * scale;
            tris.push_back({c + vec3(unit(rng), unit(rng), unit(rng)) * (0.5f * scale),
                            c + vec3(unit(rng), unit(rng), unit(rng)) * (0.5f * scale),
                            c + vec3(unit(rng), unit(rng), unit(rng)) * (0.5f * scale)});
        }
        for (int k = 0; k < 64; ++k) {
            const vec3 origin = offset + vec3(unit(rng), unit(rng), unit(rng)) * (3.0f * scale);
            const Triangle& aim = tris[size_t(k) % tris.size()];
            const vec3 target = (aim.v0 + aim.v1 + aim.v2) / 3.0f +
                                vec3(unit(rng), unit(rng), unit(rng)) * (0.3f * scale);
            // Directions of any length: object-space rays are not normalised.
            const float length = std::pow(2.0f, float(k % 7) - 3.0f);
            const float tMax = k % 4 == 0 ? 0.5f * length : kInfinity;
            ExpectLanesMatchScalar(tris, Ray{origin, tMax, (target - origin) * length, 0}, &counts);
        }
    }
    EXPECT_GT(counts.hits, 5000u);
    EXPECT_GT(counts.misses, 50000u);
}

// A grid of unit squares split into triangles: rays through their shared edges and vertices
// round edge functions to exactly 0, which the scalar test redoes in double.
TEST(TriangleIntersect4, RaysThroughSharedEdgesAndVerticesMatchTheScalarTest) {
    std::vector<Triangle> tris;
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 2; ++x) {
            const vec3 p(float(x), float(y), 0.0f);
            tris.push_back({p, p + vec3(1, 0, 0), p + vec3(1, 1, 0)});
            tris.push_back({p, p + vec3(1, 1, 0), p + vec3(0, 1, 0)});
        }
    }
    Counts counts;
    for (int i = 0; i <= 8; ++i) {
        for (int j = 0; j <= 8; ++j) {
            const vec3 target(float(i) * 0.25f, float(j) * 0.25f, 0.0f);
            for (const vec3 origin : {vec3(0.5f, 0.5f, 3.0f), vec3(-2.0f, 1.0f, 1.5f),
                                      target + vec3(0.0f, 0.0f, -1.0f)}) {
                ExpectLanesMatchScalar(tris, Ray{origin, kInfinity, target - origin, 0}, &counts);
            }
        }
    }
    EXPECT_GT(counts.hits, 150u);
}

// Rays that start on, just above or just below a triangle, toward it, along it or away: hits
// within the error bound of the origin, which the scalar test decides on the plane.
TEST(TriangleIntersect4, HitsAtTheOriginMatchTheScalarTest) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), inside(0.05f, 0.45f);
    Counts counts;
    for (int k = 0; k < 4000; ++k) {
        const float scale = std::pow(10.0f, float(k % 5) - 2.0f);
        const vec3 a = vec3(unit(rng), unit(rng), unit(rng)) * scale;
        const Triangle tri{a, a + vec3(unit(rng), unit(rng), unit(rng)) * scale,
                           a + vec3(unit(rng), unit(rng), unit(rng)) * scale};
        const vec3 n = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
        const vec3 onSurface =
            tri.v0 + (tri.v1 - tri.v0) * inside(rng) + (tri.v2 - tri.v0) * inside(rng);
        const float lift = float(k % 3 - 1) * 1e-6f * scale;
        const vec3 origin = onSurface + glm::normalize(n) * lift;
        const vec3 dir = k % 4 == 0 ? -n : vec3(unit(rng), unit(rng), unit(rng));
        const std::vector<Triangle> tris{tri, tri, {tri.v0, tri.v2, tri.v1}};
        ExpectLanesMatchScalar(tris, Ray{origin, kInfinity, dir, 0}, &counts);
    }
    EXPECT_GT(counts.hits, 100u);
}

TEST(TriangleIntersect4, DegenerateAndNonFiniteTrianglesMatchTheScalarTest) {
    const float nan = std::nanf(""), inf = kInfinity;
    const std::vector<Triangle> tris{
        {vec3(0, 0, 0), vec3(1, 0, 0), vec3(2, 0, 0)},                    // a line
        {vec3(0.5f, 0.5f, 0), vec3(0.5f, 0.5f, 0), vec3(0.5f, 0.5f, 0)},  // a point
        {vec3(nan, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)},
        {vec3(0, 0, 0), vec3(inf, 0, 0), vec3(0, 1, 0)},
        {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)},  // an ordinary one among them
        {vec3(-3e38f, 0, 0), vec3(3e38f, 0, 0), vec3(0, 3e38f, 0)},
        {vec3(0, 0, 1e-30f), vec3(1e-30f, 0, 1e-30f), vec3(0, 1e-30f, 1e-30f)},
    };
    Counts counts;
    for (const vec3 origin :
         {vec3(0.25f, 0.25f, 2.0f), vec3(0.5f, 0.5f, -1.0f), vec3(1e-31f, 1e-31f, 1.0f)}) {
        for (const vec3 target : {vec3(0.25f, 0.25f, 0.0f), vec3(0.5f, 0.0f, 0.0f),
                                  vec3(0.5f, 0.5f, 0.0f), vec3(1e-31f, 1e-31f, 0.0f)})
            ExpectLanesMatchScalar(tris, Ray{origin, kInfinity, target - origin, 0}, &counts);
    }
    EXPECT_GT(counts.hits, 4u);
}

// The scalar loop over a leaf that the helpers stand for: each triangle against the closest hit
// so far, a later one at equal t taking its place.
int ScalarClosest(const std::vector<Triangle>& tris, const RaySetup& r, float& tMax,
                  TriangleHit* hit) {
    int best = -1;
    for (size_t i = 0; i < tris.size(); ++i) {
        TriangleHit h;
        if (!IntersectTriangle(tris[i], r, tMax, &h)) continue;
        tMax = h.t;
        *hit = h;
        best = int(i);
    }
    return best;
}

void ExpectHelpersMatchScalarLoop(const std::vector<Triangle>& tris, const Ray& ray) {
    const RaySetup r = MakeRaySetup(ray);
    float tScalar = ray.tMax, tWide = ray.tMax;
    TriangleHit scalarHit{}, wideHit{};
    const int scalar = ScalarClosest(tris, r, tScalar, &scalarHit);
    const int wide = ClosestTriangle(tris.data(), uint32_t(tris.size()), r, tWide, &wideHit);
    ASSERT_EQ(wide, scalar);
    EXPECT_EQ(std::bit_cast<uint32_t>(tWide), std::bit_cast<uint32_t>(tScalar));
    if (scalar >= 0) {
        EXPECT_EQ(std::bit_cast<uint32_t>(wideHit.b1), std::bit_cast<uint32_t>(scalarHit.b1));
        EXPECT_EQ(std::bit_cast<uint32_t>(wideHit.b2), std::bit_cast<uint32_t>(scalarHit.b2));
    }
    bool anyScalar = false;
    for (const Triangle& tri : tris) {
        TriangleHit h;
        anyScalar = anyScalar || IntersectTriangle(tri, r, ray.tMax, &h);
    }
    EXPECT_EQ(AnyTriangle(tris.data(), uint32_t(tris.size()), r, ray.tMax), anyScalar);
}

// Leaves of 1 to 8 triangles on a small integer lattice (exact ties, edge functions of 0),
// copies and flipped copies among them, with tMax unbounded or at a hit's exact t.
TEST(TriangleIntersect4, LeafHelpersMatchTheScalarLoopOnRandomLeaves) {
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> coord(-3, 3), size(1, 8), pick(0, 3);
    for (int k = 0; k < 20000; ++k) {
        std::vector<Triangle> tris;
        const int n = size(rng);
        while (int(tris.size()) < n) {
            const int kind = tris.empty() ? 0 : pick(rng);
            if (kind == 1) {
                tris.push_back(tris[size_t(rng() % tris.size())]);
            } else if (kind == 2) {
                const Triangle& t = tris[size_t(rng() % tris.size())];
                tris.push_back({t.v0, t.v2, t.v1});
            } else {
                auto point = [&] {
                    return vec3(float(coord(rng)), float(coord(rng)), 0.5f * float(coord(rng)));
                };
                tris.push_back({point(), point(), point()});
            }
        }
        const vec3 origin(float(coord(rng)), float(coord(rng)), 4.0f + float(pick(rng)));
        const vec3 target(0.5f * float(coord(rng)), 0.5f * float(coord(rng)), 0.0f);
        Ray ray{origin, kInfinity, target - origin, 0};
        if (k % 2 == 1) {
            const RaySetup r = MakeRaySetup(ray);
            float t = kInfinity;
            TriangleHit h;
            if (ScalarClosest(tris, r, t, &h) >= 0) ray.tMax = t;
        }
        ExpectHelpersMatchScalarLoop(tris, ray);
    }
}

// A hit whose t is subnormal can be rejected by the scalar test when tMax is that very t (its
// early exit's slack is relative): a copy of the triangle later in the leaf is then no hit in the
// scalar loop, and the leaf helpers must agree.
TEST(TriangleIntersect4, SubnormalHitsChooseAsTheScalarLoop) {
    const Triangle tiny{vec3(-1, 1, 8 * 0x1p-149f), vec3(1, 2, 4 * 0x1p-149f),
                        vec3(0, -1, 5 * 0x1p-149f)};
    ExpectHelpersMatchScalarLoop({tiny, tiny}, Ray{vec3(0.0f), kInfinity, vec3(0, 0, 1), 0});
    ExpectHelpersMatchScalarLoop({tiny, tiny, tiny}, Ray{vec3(0.0f), kInfinity, vec3(0, 0, 1), 0});
    const Triangle far{vec3(-1, 3, -2), vec3(-3, -2, -0x1.8p-120f), vec3(2, -4, -4)};
    ExpectHelpersMatchScalarLoop({far, far},
                                 Ray{vec3(-2, 0, -1), kInfinity, vec3(1, -3, 0x1.8p+125f), 0});
}

// The leaf helpers: of hits at equal t the later triangle wins, as in the scalar loop, within a
// group of four and across groups; hits beyond tMax are none; AnyTriangle answers as any scalar
// test would.
TEST(TriangleIntersect4, LeafHelpersChooseAsTheScalarLoop) {
    const Triangle near{vec3(-1, -1, 1), vec3(1, -1, 1), vec3(0, 1, 1)};
    const Triangle far{vec3(-1, -1, 3), vec3(1, -1, 3), vec3(0, 1, 3)};
    const Triangle aside{vec3(5, 5, 0), vec3(6, 5, 0), vec3(5, 6, 0)};
    const std::vector<Triangle> tris{far, aside, near, far, near, aside};
    const RaySetup r = MakeRaySetup(Ray{vec3(0, 0, 0), kInfinity, vec3(0, 0, 1), 0});
    float tMax = kInfinity;
    TriangleHit hit;
    EXPECT_EQ(ClosestTriangle(tris.data(), uint32_t(tris.size()), r, tMax, &hit), 4);
    EXPECT_EQ(tMax, 1.0f);
    EXPECT_EQ(hit.t, 1.0f);
    float shortRay = 0.5f;
    EXPECT_EQ(ClosestTriangle(tris.data(), uint32_t(tris.size()), r, shortRay, &hit), -1);
    EXPECT_EQ(shortRay, 0.5f);
    const std::vector<Triangle> oneGroup{near, aside, near};
    float groupTMax = kInfinity;
    EXPECT_EQ(ClosestTriangle(oneGroup.data(), 3, r, groupTMax, &hit), 2);
    EXPECT_TRUE(AnyTriangle(tris.data() + 3, 3, r, 2.0f));
    EXPECT_FALSE(AnyTriangle(tris.data(), 2, r, 2.0f));  // far lies beyond, aside off the ray
    EXPECT_FALSE(AnyTriangle(&aside, 1, r, kInfinity));
}

}  // namespace
}  // namespace rtrt
