// The slab test's hard cases: zero and negative-zero direction components, rays lying in a box
// face, flat boxes, NaN rays.
#include "engine/bvh/slab_test.h"

#include <gtest/gtest.h>

namespace rtrt {
namespace {

bool Hits(vec3 lo, vec3 hi, vec3 origin, vec3 dir, float tMax = kInfinity) {
    float t;
    return SlabTest(lo, hi, MakeRaySetup(Ray{origin, tMax, dir, 0}), tMax, &t);
}

TEST(SlabTest, AxisAlignedRayWithZeroComponentsHitsAndMisses) {
    EXPECT_TRUE(Hits(vec3(-1), vec3(1), vec3(0, 0, -5), vec3(0, 0, 1)));
    EXPECT_FALSE(Hits(vec3(-1), vec3(1), vec3(2, 0, -5), vec3(0, 0, 1)));
}

TEST(SlabTest, NegativeZeroComponentsBehaveLikeZero) {
    EXPECT_TRUE(Hits(vec3(-1), vec3(1), vec3(0, 0, -5), vec3(-0.0f, -0.0f, 1)));
    EXPECT_FALSE(Hits(vec3(-1), vec3(1), vec3(0, 1.5f, -5), vec3(-0.0f, -0.0f, 1)));
}

TEST(SlabTest, RayInAFacePlaneHits) {
    // Origin exactly on the x = 1 and x = -1 planes with dx = +0 and -0: 0 * inf = NaN lanes.
    for (float x : {-1.0f, 1.0f})
        for (float dx : {0.0f, -0.0f}) {
            EXPECT_TRUE(Hits(vec3(-1), vec3(1), vec3(x, 0, -5), vec3(dx, 0, 1))) << x << " " << dx;
            EXPECT_TRUE(Hits(vec3(-1), vec3(1), vec3(x, 1, -5), vec3(dx, -0.0f, 1))) << "edge";
        }
}

TEST(SlabTest, FlatBoxIsHit) {
    EXPECT_TRUE(Hits(vec3(-1, 0, -1), vec3(1, 0, 1), vec3(0.5f, 3, 0.2f), vec3(0, -1, 0)));
    EXPECT_TRUE(Hits(vec3(-1, 0, -1), vec3(1, 0, 1), vec3(-3, 0, 0), vec3(1, 0, 0)));  // in plane
    EXPECT_FALSE(Hits(vec3(-1, 0, -1), vec3(1, 0, 1), vec3(0.5f, 3, 0.2f), vec3(0, 1, 0)));
}

TEST(SlabTest, RespectsTMaxAndStartsAtZero) {
    EXPECT_FALSE(Hits(vec3(-1), vec3(1), vec3(0, 0, -5), vec3(0, 0, 1), 3.9f));
    EXPECT_TRUE(Hits(vec3(-1), vec3(1), vec3(0, 0, -5), vec3(0, 0, 1), 4.0f));
    EXPECT_TRUE(Hits(vec3(-1), vec3(1), vec3(0), vec3(0, 0, 1)));         // origin inside
    EXPECT_FALSE(Hits(vec3(-1), vec3(1), vec3(0, 0, 5), vec3(0, 0, 1)));  // box behind
}

TEST(SlabTest, NanAndInfiniteRaysAreNotTraceable) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(IsTraceable(Ray{vec3(0), kInfinity, vec3(nan, 0, 1), 0}));
    EXPECT_FALSE(IsTraceable(Ray{vec3(kInfinity, 0, 0), kInfinity, vec3(0, 0, 1), 0}));
    EXPECT_FALSE(IsTraceable(Ray{vec3(0), kInfinity, vec3(0), 0}));
    EXPECT_FALSE(IsTraceable(Ray{vec3(0), nan, vec3(0, 0, 1), 0}));
    EXPECT_TRUE(IsTraceable(Ray{vec3(0), kInfinity, vec3(0, 0, 1), 0}));
    // Large but finite coordinates are fine (their sum would overflow).
    EXPECT_TRUE(IsTraceable(Ray{vec3(3e38f), kInfinity, vec3(3e38f, 3e38f, 1), 0}));
}

}  // namespace
}  // namespace rtrt
