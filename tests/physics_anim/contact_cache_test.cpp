// ContactCache: each pair's run is found by the pair in that order, with its generations; pairs
// not cached, reversed or with a reused index find nothing; the first of two runs of one pair
// wins.
#include "engine/physics_anim/contact_cache.h"

#include <gtest/gtest.h>

#include <vector>

namespace rtrt::physics {
namespace {

using ecs::Entity;

CachedContact At(Entity a, Entity b, float impulse) {
    return {a, b, vec3(impulse, 0.0f, 0.0f), impulse, 0.0f, 0.0f};
}

TEST(ContactCacheTest, FindsEachPairsRunAndNothingElse) {
    ContactCache cache;
    std::vector<CachedContact>& entries = cache.Entries();
    // 3,000 pairs of 1 to 4 contacts each; a pair's impulses encode it.
    for (uint32_t p = 0; p < 3000; ++p) {
        const Entity a{p, 1};
        const Entity b{p * 7 + 1, 2};
        for (uint32_t k = 0; k <= p % 4; ++k) entries.push_back(At(a, b, float(p * 10 + k)));
    }
    cache.Index();
    for (uint32_t p = 0; p < 3000; ++p) {
        const std::span<const CachedContact> run = cache.Find({p, 1}, {p * 7 + 1, 2});
        ASSERT_EQ(run.size(), p % 4 + 1) << "pair " << p;
        for (uint32_t k = 0; k < run.size(); ++k) EXPECT_EQ(run[k].normalImpulse, p * 10 + k);
        EXPECT_TRUE(cache.Find({p * 7 + 1, 2}, {p, 1}).empty()) << "reversed pair " << p;
        EXPECT_TRUE(cache.Find({p, 2}, {p * 7 + 1, 2}).empty()) << "other generation " << p;
    }
    EXPECT_TRUE(cache.Find({5000, 1}, {1, 2}).empty());
}

TEST(ContactCacheTest, SameIndicesOtherGenerationsAreOtherPairs) {
    ContactCache cache;
    cache.Entries() = {At({4, 1}, {9, 1}, 1.0f), At({4, 2}, {9, 1}, 2.0f),
                       At({4, 2}, {9, 1}, 3.0f)};
    cache.Index();
    ASSERT_EQ(cache.Find({4, 1}, {9, 1}).size(), 1u);
    EXPECT_EQ(cache.Find({4, 1}, {9, 1})[0].normalImpulse, 1.0f);
    ASSERT_EQ(cache.Find({4, 2}, {9, 1}).size(), 2u);
    EXPECT_EQ(cache.Find({4, 2}, {9, 1})[1].normalImpulse, 3.0f);
}

TEST(ContactCacheTest, FirstRunOfARepeatedPairWinsAndEmptyFindsNothing) {
    ContactCache cache;
    EXPECT_TRUE(cache.Find({1, 1}, {2, 1}).empty());  // never indexed
    cache.Entries() = {At({1, 1}, {2, 1}, 1.0f), At({3, 1}, {2, 1}, 2.0f),
                       At({1, 1}, {2, 1}, 3.0f)};
    cache.Index();
    ASSERT_EQ(cache.Find({1, 1}, {2, 1}).size(), 1u);
    EXPECT_EQ(cache.Find({1, 1}, {2, 1})[0].normalImpulse, 1.0f);
    cache.Entries().clear();
    cache.Index();
    EXPECT_TRUE(cache.Find({1, 1}, {2, 1}).empty());
}

}  // namespace
}  // namespace rtrt::physics
