// Contact colouring: a colour never holds two manifolds that move the same body, bodies that do
// not move constrain nothing, and a body with more than 64 manifolds spills into the overflow.
#include "engine/physics_anim/contact_coloring.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <utility>
#include <vector>

namespace rtrt::physics {
namespace {

TEST(ContactColoringTest, NoColourMovesABodyTwice) {
    constexpr uint32_t kBodies = 500;
    std::mt19937 random(3);
    std::uniform_int_distribution<uint32_t> body(0, kBodies - 1);
    std::vector<bool> moves(kBodies);
    for (uint32_t i = 0; i < kBodies; ++i) moves[i] = i % 7 != 0;  // every 7th rests
    ContactColoring coloring;
    coloring.Reset(kBodies);
    std::vector<std::set<uint32_t>> moved(ContactColoring::kColors);
    uint32_t highest = 0;
    for (int m = 0; m < 4000; ++m) {
        const uint32_t a = body(random);
        const uint32_t b = body(random);
        if (a == b) continue;
        const uint32_t color = coloring.Assign(a, moves[a], b, moves[b]);
        ASSERT_LT(color, ContactColoring::kOverflow);  // 16 manifolds per body on average
        highest = std::max(highest, color);
        for (const uint32_t i : {a, b}) {
            if (moves[i]) {
                EXPECT_TRUE(moved[color].insert(i).second) << "body " << i;
            }
        }
    }
    // Greedy colouring needs at most one more colour than a body's manifolds.
    EXPECT_LT(highest, 40u);
}

TEST(ContactColoringTest, StillBodiesConstrainNothing) {
    ContactColoring coloring;
    coloring.Reset(10);
    // Body 0 is the floor: every body on it can be solved at once.
    for (uint32_t i = 1; i < 10; ++i) EXPECT_EQ(coloring.Assign(0, false, i, true), 0u);
    // Two moving bodies already in colour 0 push the next manifold between them to colour 1.
    EXPECT_EQ(coloring.Assign(1, true, 2, true), 1u);
    EXPECT_EQ(coloring.Assign(2, true, 3, true), 2u);
    // A manifold between two still bodies (never solved) takes the first colour.
    EXPECT_EQ(coloring.Assign(4, false, 5, false), 0u);
    // Reset forgets.
    coloring.Reset(10);
    EXPECT_EQ(coloring.Assign(1, true, 2, true), 0u);
}

TEST(ContactColoringTest, ABodyWithMoreThanSixtyFourManifoldsOverflows) {
    ContactColoring coloring;
    coloring.Reset(100);
    for (uint32_t i = 1; i <= ContactColoring::kColors; ++i) {
        EXPECT_EQ(coloring.Assign(0, true, i, true), i - 1);
    }
    EXPECT_EQ(coloring.Assign(0, true, 99, true), ContactColoring::kOverflow);
    // The overflow does not mark the bodies: another body's manifolds still find colours.
    EXPECT_EQ(coloring.Assign(99, true, 98, true), 0u);
}

}  // namespace
}  // namespace rtrt::physics
