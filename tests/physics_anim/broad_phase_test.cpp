// Sort and sweep (in strips) finds exactly the overlapping pairs that brute force finds.
#include "engine/physics_anim/broad_phase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace rtrt::physics {
namespace {

using Pairs = std::vector<std::pair<uint32_t, uint32_t>>;

bool Overlap(const BroadPhaseBox& a, const BroadPhaseBox& b) {
    for (int k = 0; k < 3; ++k) {
        if (a.min[k] > b.max[k] || b.min[k] > a.max[k]) return false;
    }
    return true;
}

Pairs BruteForce(const std::vector<BroadPhaseBox>& boxes) {
    Pairs pairs;
    for (uint32_t i = 0; i < boxes.size(); ++i) {
        for (uint32_t j = i + 1; j < boxes.size(); ++j) {
            if (!(boxes[i].isStatic && boxes[j].isStatic) && Overlap(boxes[i], boxes[j]))
                pairs.emplace_back(i, j);
        }
    }
    return pairs;
}

std::vector<BroadPhaseBox> RandomBoxes(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    auto unit = [&] { return static_cast<float>(rng() >> 8) * 0x1p-24f; };
    std::vector<BroadPhaseBox> boxes;
    for (uint32_t i = 0; i < count; ++i) {
        const vec3 c(unit() * 20.0f, unit() * 4.0f, unit() * 20.0f);
        const vec3 h(0.1f + unit() * 0.6f);
        boxes.push_back({c - h, c + h, unit() < 0.2f});
    }
    return boxes;
}

TEST(BroadPhaseTest, SweepFindsTheSamePairsAsBruteForce) {
    for (uint32_t seed = 1; seed <= 5; ++seed) {
        const std::vector<BroadPhaseBox> boxes = RandomBoxes(800, seed);
        SweepAndPrune sweep;
        Pairs found;
        sweep.FindPairs(boxes, found);
        std::sort(found.begin(), found.end());
        const Pairs expected = BruteForce(boxes);
        EXPECT_FALSE(expected.empty());
        EXPECT_EQ(found, expected) << "seed " << seed;
    }
}

// One SweepAndPrune over many steps, as the physics uses it: boxes that drift a little (the sort
// starts from the last order, in chunks of 1024), a box that leaps from one end to the other (from
// the last chunk to the first place) and one that leaps back, a step where they all jump (too far
// for that: a full sort), a box count that changes, and the spread turning to another axis. Every
// step gives brute force's pairs, in the order a fresh SweepAndPrune gives.
TEST(BroadPhaseTest, StepsFromTheLastOrderFindTheSamePairsAsAFreshSweep) {
    std::mt19937 rng(17);
    auto unit = [&] { return static_cast<float>(rng() >> 8) * 0x1p-24f; };
    std::vector<BroadPhaseBox> boxes = RandomBoxes(2600, 9);
    SweepAndPrune kept;
    for (int step = 0; step < 12; ++step) {
        const float move = step == 5 ? 20.0f : 0.05f;
        for (BroadPhaseBox& box : boxes) {
            const vec3 d(move * (unit() - 0.5f), move * (unit() - 0.5f), move * (unit() - 0.5f));
            box.min += d;
            box.max += d;
        }
        const auto diagonal = [](const BroadPhaseBox& a, const BroadPhaseBox& b) {
            return a.min.x + a.min.z < b.min.x + b.min.z;
        };
        if (step == 3) {  // the box furthest along x and z leaps to before all the others
            const auto far = std::max_element(boxes.begin(), boxes.end(), diagonal);
            far->max -= vec3(25.0f, 0.0f, 25.0f);
            far->min -= vec3(25.0f, 0.0f, 25.0f);
        }
        if (step == 4) {  // and the first box leaps to beyond all the others
            const auto near = std::min_element(boxes.begin(), boxes.end(), diagonal);
            near->max += vec3(50.0f, 0.0f, 50.0f);
            near->min += vec3(50.0f, 0.0f, 50.0f);
        }
        if (step == 7) boxes.resize(2300);
        if (step == 9) {  // the boxes now spread most along y
            for (BroadPhaseBox& box : boxes) {
                std::swap(box.min.x, box.min.y);
                std::swap(box.max.x, box.max.y);
            }
        }
        Pairs found;
        kept.FindPairs(boxes, found);
        SweepAndPrune fresh;
        Pairs expected;
        fresh.FindPairs(boxes, expected);
        EXPECT_EQ(found, expected) << "step " << step;
        std::vector<uint32_t> keptRanks, freshRanks;
        kept.Ranks(keptRanks);
        fresh.Ranks(freshRanks);
        EXPECT_EQ(keptRanks, freshRanks) << "step " << step;
        std::sort(found.begin(), found.end());
        EXPECT_EQ(found, BruteForce(boxes)) << "step " << step;
    }
}

// A floor's worth of small boxes (many strips) with a few walls that cross every strip, boxes
// that touch exactly on strip boundaries, and a box far away: still exactly brute force's pairs,
// each once, and the same order on a second call.
TEST(BroadPhaseTest, StripsFindEachPairOnceAmongLargeAndTouchingBoxes) {
    std::vector<BroadPhaseBox> boxes = RandomBoxes(3000, 9);
    for (BroadPhaseBox& box : boxes) {  // flatten onto a 40 x 40 floor
        box.min.x *= 2.0f;
        box.max.x = box.min.x + 0.5f;
        box.min.z *= 2.0f;
        box.max.z = box.min.z + 0.5f;
    }
    boxes.push_back({vec3(-1.0f, 0.0f, -1.0f), vec3(41.0f, 2.0f, 0.0f), true});
    boxes.push_back({vec3(-1.0f, 0.0f, -1.0f), vec3(0.0f, 2.0f, 41.0f), true});
    boxes.push_back({vec3(0.0f, 0.0f, 0.0f), vec3(41.0f, 4.0f, 41.0f), false});
    for (float z = 0.0f; z < 40.0f; z += 0.25f) {  // edge to edge along z
        boxes.push_back({vec3(7.0f, 1.0f, z), vec3(7.5f, 1.5f, z + 0.25f), false});
    }
    boxes.push_back({vec3(1000.0f), vec3(1001.0f), false});
    SweepAndPrune sweep;
    Pairs found;
    sweep.FindPairs(boxes, found);
    Pairs again;
    sweep.FindPairs(boxes, again);
    EXPECT_EQ(found, again);
    std::sort(found.begin(), found.end());
    EXPECT_EQ(std::adjacent_find(found.begin(), found.end()), found.end()) << "a pair twice";
    EXPECT_EQ(found, BruteForce(boxes));
}

// Under a pair limit the sweep stops once it has found more pairs than allowed (boxes packed
// into one place pair every two) and says so; within the limit it finds what it finds without.
TEST(BroadPhaseTest, APairLimitStopsThePackedSweep) {
    const std::vector<BroadPhaseBox> spread = RandomBoxes(1500, 4);
    Pairs unlimited, limited;
    SweepAndPrune free;
    EXPECT_TRUE(free.FindPairs(spread, unlimited));
    SweepAndPrune bounded;
    bounded.SetPairLimit(32 * spread.size());
    EXPECT_TRUE(bounded.FindPairs(spread, limited));
    EXPECT_EQ(limited, unlimited);
    const std::vector<BroadPhaseBox> packed(2000, {vec3(0.0f), vec3(1.0f), false});
    SweepAndPrune tight;
    tight.SetPairLimit(32 * packed.size());
    Pairs some;
    EXPECT_FALSE(tight.FindPairs(packed, some));
    EXPECT_LE(some.size(), 32 * packed.size() + packed.size());  // give or take a box's pairs
    EXPECT_TRUE(free.FindPairs(packed, some));                   // 1,999,000 pairs without a limit
    EXPECT_EQ(some.size(), 2000u * 1999u / 2u);
}

// Named boxes: the same pairs in the same order with each index replaced by its name, and each
// box's rank written under its name.
TEST(BroadPhaseTest, NamedBoxesGiveTheIndexPairsRenamed) {
    const std::vector<BroadPhaseBox> boxes = RandomBoxes(1500, 4);
    std::vector<uint32_t> names(boxes.size());
    for (uint32_t i = 0; i < names.size(); ++i) names[i] = 3 * i + 1 + (i % 2);  // increasing
    SweepAndPrune byIndex;
    Pairs indexed;
    byIndex.FindPairs(boxes, indexed);
    SweepAndPrune byName;
    Pairs named;
    byName.FindPairs(boxes, named, names);
    ASSERT_EQ(named.size(), indexed.size());
    ASSERT_FALSE(named.empty());
    for (size_t k = 0; k < named.size(); ++k) {
        EXPECT_EQ(named[k], std::make_pair(names[indexed[k].first], names[indexed[k].second]));
    }
    std::vector<uint32_t> ranks;
    byIndex.Ranks(ranks);
    std::vector<uint32_t> rankByName(names.back() + 1, ~0u);
    byName.Ranks(names, rankByName);
    for (uint32_t i = 0; i < boxes.size(); ++i) EXPECT_EQ(rankByName[names[i]], ranks[i]);
}

TEST(BroadPhaseTest, TouchingBoxesPairButStaticPairsDoNot) {
    std::vector<BroadPhaseBox> boxes{
        {vec3(0.0f), vec3(1.0f), false},
        {vec3(1.0f, 0.0f, 0.0f), vec3(2.0f, 1.0f, 1.0f), true},
        {vec3(1.5f, 0.0f, 0.0f), vec3(3.0f, 1.0f, 1.0f), true},
        {vec3(5.0f), vec3(6.0f), false},
    };
    SweepAndPrune sweep;
    Pairs found;
    sweep.FindPairs(boxes, found);
    EXPECT_EQ(found, (Pairs{{0, 1}}));
}

}  // namespace
}  // namespace rtrt::physics
