// SolverTiles: equal tiles across the two axes of spread, in Morton order, laid out tile by tile.
#include "engine/physics_anim/solver_tiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace rtrt::physics {
namespace {

// Unit boxes at random places on a 40 x 20 floor (x spreads most, then z), in random order.
std::vector<BroadPhaseBox> FloorBoxes(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> x(0.0f, 40.0f), y(0.0f, 2.0f), z(0.0f, 20.0f);
    std::vector<BroadPhaseBox> boxes;
    for (uint32_t i = 0; i < count; ++i) {
        const vec3 c(x(rng), y(rng), z(rng));
        boxes.push_back({c - vec3(0.5f), c + vec3(0.5f), false});
    }
    return boxes;
}

struct Assigned {
    std::vector<uint8_t> tile;
    std::vector<uint32_t> slot;
    std::vector<uint32_t> rank;  // sweep rank
};

Assigned Assign(const std::vector<BroadPhaseBox>& boxes) {
    SweepAndPrune sweep;
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    sweep.FindPairs(boxes, pairs);
    std::vector<uint32_t> to(boxes.size());
    std::iota(to.begin(), to.end(), 0u);
    Assigned out{std::vector<uint8_t>(boxes.size()), std::vector<uint32_t>(boxes.size()), {}};
    SolverTiles tiles;
    tiles.Assign(boxes, sweep, to, out.tile, out.slot);
    sweep.Ranks(out.rank);
    return out;
}

TEST(SolverTilesTest, MortonInterleavesColumnAndRow) {
    EXPECT_EQ(SolverTiles::Morton(0, 0), 0u);
    EXPECT_EQ(SolverTiles::Morton(0, 1), 1u);
    EXPECT_EQ(SolverTiles::Morton(1, 0), 2u);
    EXPECT_EQ(SolverTiles::Morton(3, 3), 15u);
    EXPECT_EQ(SolverTiles::Morton(4, 0), 32u);
    EXPECT_EQ(SolverTiles::Morton(15, 15), 255u);
}

TEST(SolverTilesTest, EqualTilesAcrossBothAxesLaidOutTileByTile) {
    constexpr uint32_t kBoxes = 5000;
    const std::vector<BroadPhaseBox> boxes = FloorBoxes(kBoxes, 7);
    const Assigned a = Assign(boxes);
    // Slots: every box one, tile by tile.
    std::vector<uint32_t> bySlot(kBoxes, UINT32_MAX);
    for (uint32_t i = 0; i < kBoxes; ++i) {
        ASSERT_LT(a.slot[i], kBoxes);
        ASSERT_EQ(bySlot[a.slot[i]], UINT32_MAX) << "slot " << a.slot[i] << " given twice";
        bySlot[a.slot[i]] = i;
    }
    for (uint32_t s = 1; s < kBoxes; ++s) EXPECT_LE(a.tile[bySlot[s - 1]], a.tile[bySlot[s]]);
    // Columns cut the sweep order (along x) in 16 equal runs, rows each column along z in 16.
    std::vector<uint32_t> count(SolverTiles::kTiles, 0);
    for (uint32_t i = 0; i < kBoxes; ++i) ++count[a.tile[i]];
    for (uint32_t t = 0; t < SolverTiles::kTiles; ++t) {
        EXPECT_GE(count[t], kBoxes / SolverTiles::kTiles - 1) << "tile " << t;
        EXPECT_LE(count[t], kBoxes / SolverTiles::kTiles + 1) << "tile " << t;
    }
    for (uint32_t i = 0; i < kBoxes; ++i) {
        for (uint32_t j = 0; j < kBoxes; ++j) {
            const uint32_t ti = a.tile[i];
            const uint32_t tj = a.tile[j];
            // Morton: column bits at odd places, row bits at even ones.
            const auto column = [](uint32_t t) {
                return (t >> 1 & 1u) | (t >> 2 & 2u) | (t >> 3 & 4u) | (t >> 4 & 8u);
            };
            const auto row = [](uint32_t t) {
                return (t & 1u) | (t >> 1 & 2u) | (t >> 2 & 4u) | (t >> 3 & 8u);
            };
            if (column(ti) < column(tj)) {
                ASSERT_LT(a.rank[i], a.rank[j]);
            } else if (column(ti) == column(tj) && row(ti) < row(tj)) {
                ASSERT_LE(boxes[i].min.z, boxes[j].min.z);
            }
        }
    }
}

// The tiles depend on the boxes, not on their order in the input.
TEST(SolverTilesTest, SameTilesWhateverTheBoxOrder) {
    const std::vector<BroadPhaseBox> boxes = FloorBoxes(3000, 11);
    std::vector<uint32_t> permutation(boxes.size());
    std::iota(permutation.begin(), permutation.end(), 0u);
    std::shuffle(permutation.begin(), permutation.end(), std::mt19937(3));
    std::vector<BroadPhaseBox> shuffled(boxes.size());
    for (uint32_t i = 0; i < boxes.size(); ++i) shuffled[permutation[i]] = boxes[i];
    const Assigned a = Assign(boxes);
    const Assigned b = Assign(shuffled);
    for (uint32_t i = 0; i < boxes.size(); ++i) {
        EXPECT_EQ(a.tile[i], b.tile[permutation[i]]) << "box " << i;
    }
}

}  // namespace
}  // namespace rtrt::physics
