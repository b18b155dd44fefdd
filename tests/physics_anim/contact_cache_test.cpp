// ContactCache: each pair's run is found by the pair in that order, with its generations; pairs
// not cached, reversed or with a reused index find nothing; the first of two runs of one pair
// wins.
#include "engine/physics_anim/contact_cache.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <utility>
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

// Index runs in parallel: many runs whose pairs share indices with other generations, and pairs
// repeated in later runs, in a random order, against a map of each pair's first run. Run on the
// threads TBB lends, many times, so that inserts of one key meet.
TEST(ContactCacheTest, ParallelIndexFindsEachPairsFirstRun) {
    std::mt19937 random(5);
    for (int round = 0; round < 20; ++round) {
        ContactCache cache;
        std::vector<CachedContact>& entries = cache.Entries();
        std::map<std::pair<uint64_t, uint64_t>, std::pair<size_t, size_t>> first;
        const auto id = [](Entity e) { return (uint64_t{e.index} << 32) | e.generation; };
        Entity previousA, previousB;
        for (int run = 0; run < 20000; ++run) {
            // 64 x 64 index pairs and 3 generations each: keys meet often.
            Entity a{uint32_t(random() % 64), uint32_t(random() % 3)};
            Entity b{uint32_t(random() % 64), uint32_t(random() % 3)};
            if (a == previousA && b == previousB) continue;  // that would extend the last run
            previousA = a;
            previousB = b;
            const size_t begin = entries.size();
            const uint32_t length = random() % 3 + 1;
            for (uint32_t k = 0; k < length; ++k) {
                entries.push_back(At(a, b, float(entries.size())));
            }
            first.try_emplace({id(a), id(b)}, begin, entries.size());
        }
        cache.Index();
        for (const auto& [pair, run] : first) {
            const Entity a{uint32_t(pair.first >> 32), uint32_t(pair.first)};
            const Entity b{uint32_t(pair.second >> 32), uint32_t(pair.second)};
            const std::span<const CachedContact> found = cache.Find(a, b);
            ASSERT_EQ(found.size(), run.second - run.first);
            EXPECT_EQ(found.data(), entries.data() + run.first);
        }
    }
}

}  // namespace
}  // namespace rtrt::physics
