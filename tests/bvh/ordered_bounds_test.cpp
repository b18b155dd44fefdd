// OrderedBounds, the GPU LBVH's centroid bounds: keys order as the floats they encode (negative,
// signed zeros, infinities), decode exactly, and a minimum over keys gives Aabb::Grow's box, NaN
// skipped, in any order.
#include "engine/bvh/build/ordered_bounds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace rtrt {
namespace {

TEST(OrderedBounds, KeysOrderAsFloatsAndDecodeExactly) {
    const std::vector<float> sorted{-kInfinity, -3.4e38f, -1.0f, -1e-45f, -0.0f,
                                    0.0f,       1e-45f,   1.0f,  3.4e38f, kInfinity};
    for (size_t i = 0; i < sorted.size(); ++i) {
        EXPECT_EQ(FloatToBits(FromOrderedKey(OrderedKey(sorted[i]))), FloatToBits(sorted[i]));
        if (i > 0) {
            EXPECT_LT(OrderedKey(sorted[i - 1]), OrderedKey(sorted[i])) << sorted[i];
        }
    }
    EXPECT_EQ(OrderedBounds::MinKey(std::nanf("")), OrderedBounds::kNone);
    EXPECT_EQ(OrderedBounds::NegMaxKey(-std::nanf("")), OrderedBounds::kNone);
}

TEST(OrderedBounds, NoPointIsTheEmptyBox) {
    OrderedBounds none;
    std::fill(none.minKey, none.minKey + 3, OrderedBounds::kNone);
    std::fill(none.negMaxKey, none.negMaxKey + 3, OrderedBounds::kNone);
    const Aabb box = none;
    EXPECT_EQ(box.min, vec3(kInfinity));
    EXPECT_EQ(box.max, vec3(-kInfinity));
}

TEST(OrderedBounds, MinimaOfKeysGiveGrowsBoxInAnyOrder) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coord(-1e4f, 1e4f);
    std::vector<vec3> points(500);
    for (vec3& p : points) p = vec3(coord(rng), coord(rng), coord(rng));
    points[3].y = std::nanf("");  // skipped on that axis only
    Aabb grown;
    for (const vec3& p : points) grown.Grow(p);
    for (int round = 0; round < 3; ++round) {
        std::shuffle(points.begin(), points.end(), rng);
        OrderedBounds keys;
        std::fill(keys.minKey, keys.minKey + 3, OrderedBounds::kNone);
        std::fill(keys.negMaxKey, keys.negMaxKey + 3, OrderedBounds::kNone);
        for (const vec3& p : points) {
            for (int a = 0; a < 3; ++a) {
                keys.minKey[a] = std::min(keys.minKey[a], OrderedBounds::MinKey(p[a]));
                keys.negMaxKey[a] = std::min(keys.negMaxKey[a], OrderedBounds::NegMaxKey(p[a]));
            }
        }
        const Aabb box = keys;
        EXPECT_EQ(box.min, grown.min);
        EXPECT_EQ(box.max, grown.max);
    }
}

}  // namespace
}  // namespace rtrt
