// Polygon faces split into triangles (polygon_triangulation.h): fans where convex, ear clipping
// where concave, checked by area and by where the triangles lie.
#include "game/assets/polygon_triangulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

namespace rtrt {
namespace {

struct Split {
    std::vector<glm::uvec3> triangles;
    double area = 0.0;           // the sum of the triangles' areas
    vec3 normal{0.0f};           // of the first triangle
    bool allAlongNormal = true;  // every triangle faces the first one's way
};

Split Triangulate(const std::vector<vec3>& corners, PolygonTriangulator& triangulator) {
    Split split;
    triangulator.Triangulate(corners, split.triangles);
    for (const glm::uvec3& t : split.triangles) {
        const glm::dvec3 n = glm::cross(glm::dvec3(corners[t.y] - corners[t.x]),
                                        glm::dvec3(corners[t.z] - corners[t.x]));
        split.area += 0.5 * glm::length(n);
        if (split.normal == vec3(0.0f)) split.normal = vec3(glm::normalize(n));
        split.allAlongNormal &= glm::dot(glm::dvec3(split.normal), n) >= 0.0;
    }
    return split;
}

Split Triangulate(const std::vector<vec3>& corners) {
    PolygonTriangulator triangulator;
    return Triangulate(corners, triangulator);
}

// Whether any triangle's centroid lies inside the axis-aligned rectangle (x0, y0)-(x1, y1).
bool AnyCentroidIn(const std::vector<vec3>& corners, const std::vector<glm::uvec3>& triangles,
                   float x0, float y0, float x1, float y1) {
    for (const glm::uvec3& t : triangles) {
        const vec3 c = (corners[t.x] + corners[t.y] + corners[t.z]) / 3.0f;
        if (c.x > x0 && c.x < x1 && c.y > y0 && c.y < y1) return true;
    }
    return false;
}

// POLYGON's corners from corner START on: the same polygon, listed from another corner.
std::vector<vec3> FromCorner(const std::vector<vec3>& polygon, size_t start) {
    std::vector<vec3> out;
    for (size_t i = 0; i < polygon.size(); ++i)
        out.push_back(polygon[(start + i) % polygon.size()]);
    return out;
}

// A U of 3 x 3 with a notch of 1 x 2 between its arms: area 7.
const std::vector<vec3> kU = {{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {2, 3, 0},
                              {2, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}};

TEST(PolygonTriangulation, ConvexPolygonsAreFansFromTheFirstCorner) {
    const std::vector<vec3> pentagon = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5f, 2, 0}, {0, 1, 0}};
    const Split split = Triangulate(pentagon);
    ASSERT_EQ(split.triangles.size(), 3u);
    EXPECT_EQ(split.triangles[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(split.triangles[1], glm::uvec3(0, 2, 3));
    EXPECT_EQ(split.triangles[2], glm::uvec3(0, 3, 4));
}

TEST(PolygonTriangulation, ConcavePolygonsCoverExactlyTheirArea) {
    const Split split = Triangulate(kU);
    ASSERT_EQ(split.triangles.size(), 6u);
    EXPECT_NEAR(split.area, 7.0, 1e-9);
    EXPECT_FALSE(AnyCentroidIn(kU, split.triangles, 1.0f, 1.0f, 2.0f, 3.0f));
    EXPECT_EQ(split.normal, vec3(0.0f, 0.0f, 1.0f));
    EXPECT_TRUE(split.allAlongNormal);
    EXPECT_TRUE(Triangulate(kU).triangles == split.triangles);  // the same every time
}

TEST(PolygonTriangulation, EveryStartingCornerAndBothWindings) {
    for (size_t start = 0; start < kU.size(); ++start) {
        std::vector<vec3> rotated, reversed;
        for (size_t i = 0; i < kU.size(); ++i) {
            rotated.push_back(kU[(start + i) % kU.size()]);
            reversed.push_back(kU[(start + kU.size() - i) % kU.size()]);
        }
        const Split forward = Triangulate(rotated), backward = Triangulate(reversed);
        EXPECT_NEAR(forward.area, 7.0, 1e-9) << start;
        EXPECT_NEAR(backward.area, 7.0, 1e-9) << start;
        EXPECT_EQ(forward.normal, vec3(0.0f, 0.0f, 1.0f)) << start;
        EXPECT_EQ(backward.normal, vec3(0.0f, 0.0f, -1.0f)) << start;
        EXPECT_TRUE(forward.allAlongNormal && backward.allAlongNormal) << start;
        EXPECT_FALSE(AnyCentroidIn(rotated, forward.triangles, 1.0f, 1.0f, 2.0f, 3.0f));
        EXPECT_FALSE(AnyCentroidIn(reversed, backward.triangles, 1.0f, 1.0f, 2.0f, 3.0f));
    }
}

TEST(PolygonTriangulation, ArrowheadFromEveryCorner) {
    // The notch of the arrowhead is its reflex corner (0, 0); area 4. From a wing, the fan
    // covered 12.
    const std::vector<vec3> arrow = {{0, 2, 0}, {-2, -2, 0}, {0, 0, 0}, {2, -2, 0}};
    for (size_t start = 0; start < arrow.size(); ++start) {
        const std::vector<vec3> rotated = FromCorner(arrow, start);
        const Split split = Triangulate(rotated);
        EXPECT_NEAR(split.area, 4.0, 1e-9) << start;
        EXPECT_TRUE(split.allAlongNormal) << start;
    }
}

TEST(PolygonTriangulation, TiltedPlanesAndLargeCoordinates) {
    // The U turned 60 degrees about x and moved far away: the same area and notch.
    const float c = 0.5f, s = std::sqrt(3.0f) / 2.0f;
    std::vector<vec3> tilted;
    for (vec3 p : kU)
        tilted.push_back(vec3(p.x, c * p.y, s * p.y) + vec3(1000.0f, -500.0f, 250.0f));
    const Split split = Triangulate(tilted);
    EXPECT_NEAR(split.area, 7.0, 1e-3);
    EXPECT_TRUE(split.allAlongNormal);
    EXPECT_NEAR(glm::distance(split.normal, vec3(0.0f, -s, c)), 0.0f, 1e-4f);
}

TEST(PolygonTriangulation, RepeatedCornersCountOnce) {
    std::vector<vec3> doubled;
    for (vec3 p : kU) doubled.insert(doubled.end(), {p, p});
    const Split split = Triangulate(doubled);
    ASSERT_EQ(split.triangles.size(), 6u);
    EXPECT_NEAR(split.area, 7.0, 1e-9);
    for (const glm::uvec3& t : split.triangles) {
        EXPECT_EQ(t.x % 2, 0u);  // the first of each pair stands for both
        EXPECT_EQ(t.y % 2, 0u);
        EXPECT_EQ(t.z % 2, 0u);
    }
    EXPECT_TRUE(Triangulate({{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}}).triangles.empty());
}

TEST(PolygonTriangulation, PolygonsTouchingThemselvesAtACornerFromEveryStart) {
    // Two triangles joined at the origin, of areas 2 and 2 (an hourglass), and two lobes joined
    // at one corner (areas 5 and 7): a triangle across the pinch lay outside the polygon.
    const std::vector<vec3> hourglass = {{0, 0, 0}, {2, -1, 0}, {2, 1, 0},
                                         {0, 0, 0}, {-2, 1, 0}, {-2, -1, 0}};
    const std::vector<vec3> lobes = {{0, 0, 0}, {-3, 1, 0}, {-4, -2, 0},
                                     {0, 0, 0}, {6, -1, 0}, {2, 2, 0}};
    for (const auto& [polygon, area] : {std::pair{hourglass, 4.0}, std::pair{lobes, 12.0}}) {
        for (size_t start = 0; start < polygon.size(); ++start) {
            const std::vector<vec3> rotated = FromCorner(polygon, start);
            PolygonTriangulator triangulator;
            const Split split = Triangulate(rotated, triangulator);
            EXPECT_NEAR(split.area, area, 1e-9) << start;
            EXPECT_TRUE(split.allAlongNormal) << start;
            EXPECT_EQ(triangulator.NoEar(), 0u) << start;
        }
    }
}

TEST(PolygonTriangulation, AHoleReachedThroughASlitStaysOpen) {
    // A 4 x 4 square with a 2 x 2 hole in its middle, joined to the outside by a slit of zero
    // width along y = 1 from x = 0 to 1: area 12, and nothing in the hole.
    const std::vector<vec3> slit = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0},
                                    {0, 1, 0}, {1, 1, 0}, {1, 3, 0}, {3, 3, 0},
                                    {3, 1, 0}, {1, 1, 0}, {0, 1, 0}};
    PolygonTriangulator triangulator;
    const Split split = Triangulate(slit, triangulator);
    EXPECT_NEAR(split.area, 12.0, 1e-9);
    EXPECT_TRUE(split.allAlongNormal);
    EXPECT_FALSE(AnyCentroidIn(slit, split.triangles, 1.0f, 1.0f, 3.0f, 3.0f));
    EXPECT_EQ(triangulator.NoEar(), 0u);
}

TEST(PolygonTriangulation, ZeroWidthSpikesAreDropped) {
    // A 2 x 2 square with a spike of no width out of its top edge: it left no ear to clip, and
    // the fan then covered 4 to 8 from different starting corners.
    const std::vector<vec3> spike = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {1, 2, 0},
                                     {1, 4, 0}, {1, 2, 0}, {0, 2, 0}};
    for (size_t start = 0; start < spike.size(); ++start) {
        const std::vector<vec3> rotated = FromCorner(spike, start);
        PolygonTriangulator triangulator;
        const Split split = Triangulate(rotated, triangulator);
        EXPECT_NEAR(split.area, 4.0, 1e-9) << start;
        EXPECT_EQ(triangulator.NoEar(), 0u) << start;
    }
}

TEST(PolygonTriangulation, CollinearCornersAreNoConcavePolygon) {
    PolygonTriangulator triangulator;
    const Split split =
        Triangulate({{0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {2, 0, 0}, {5, 0, 0}}, triangulator);
    EXPECT_EQ(split.triangles.size(), 3u);
    EXPECT_EQ(split.area, 0.0);
    EXPECT_EQ(triangulator.NoEar(), 0u);  // no warning for a face without area
}

TEST(PolygonTriangulation, ACrossedPolygonWithNoEarIsFannedAndCounted) {
    // A hexagon whose edges cross (found by a search of small random ones): no ear is left to
    // clip, so it is the fan from its first corner, counted for the loader's warning.
    const std::vector<vec3> crossed = {{2, 0, 0}, {0, 4, 0}, {3, 3, 0},
                                       {0, 0, 0}, {1, 1, 0}, {3, 4, 0}};
    PolygonTriangulator triangulator;
    const Split split = Triangulate(crossed, triangulator);
    EXPECT_EQ(triangulator.NoEar(), 1u);
    ASSERT_EQ(split.triangles.size(), 4u);
    for (uint32_t i = 0; i < 4; ++i) EXPECT_EQ(split.triangles[i], glm::uvec3(0, i + 1, i + 2));
}

// Ear clipping finds ears in a bowtie, and a star drawn in one stroke turns one way at every
// corner as a convex polygon does: both had been split without the warning the loaders promise.
// The bowtie's lobes cancel in its Newell normal, so it is seen along its narrowest spread.
TEST(PolygonTriangulation, PolygonsWhoseEdgesCrossAreFannedAndCounted) {
    const std::vector<std::vector<vec3>> crossed = {
        {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}},                         // bowtie in z = 0
        {{0, 0, 5}, {0, 1, 6}, {0, 1, 5}, {0, 0, 6}},                         // bowtie in x = 0
        {{0, 3, 0}, {2, -3, 0}, {-3, 1, 0}, {3, 1, 0}, {-2, -3, 0}},          // pentagram
        {{0, 0, 0}, {4, 0, 0}, {4, 2, 0}, {2, 2, 0}, {2, -1, 0}, {0, 2, 0}},  // folded hexagon
    };
    for (size_t k = 0; k < crossed.size(); ++k) {
        SCOPED_TRACE(k);
        PolygonTriangulator triangulator;
        const Split split = Triangulate(crossed[k], triangulator);
        EXPECT_EQ(triangulator.NoEar(), 1u);
        ASSERT_EQ(split.triangles.size(), crossed[k].size() - 2);
        for (uint32_t i = 0; i < split.triangles.size(); ++i)
            EXPECT_EQ(split.triangles[i], glm::uvec3(0, i + 1, i + 2));
    }
    // Touching is not crossing: a square pinched to a corner of itself, the U, a plain square.
    for (const std::vector<vec3>& simple :
         {kU, std::vector<vec3>{{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 0}},
          std::vector<vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}}) {
        PolygonTriangulator triangulator;
        Triangulate(simple, triangulator);
        EXPECT_EQ(triangulator.NoEar(), 0u);
    }
}

// The crossing check of a huge convex polygon is linear and spends nothing: a convex 24,000-gon's
// pairwise check had emptied the file's ear-test budget, and a concave polygon after it was
// fanned.
TEST(PolygonTriangulation, AHugeConvexPolygonLeavesTheBudgetWhole) {
    // Exactly convex in float: the primitive integer vectors of length at most 100 per axis,
    // walked in the order of their angles, as edges (each direction once, so every corner turns
    // left; they sum to zero, so the walk closes).
    std::vector<glm::ivec2> edges;
    for (int a = -100; a <= 100; ++a)
        for (int b = -100; b <= 100; ++b)
            if (std::gcd(a, b) == 1) edges.emplace_back(a, b);
    std::sort(edges.begin(), edges.end(), [](glm::ivec2 p, glm::ivec2 q) {
        return std::atan2(double(p.y), double(p.x)) < std::atan2(double(q.y), double(q.x));
    });
    std::vector<vec3> convex;
    glm::ivec2 at(0);
    for (const glm::ivec2& e : edges) {
        convex.push_back(vec3(float(at.x), float(at.y), 0.0f));
        at += e;
    }
    ASSERT_GT(convex.size(), 23200u);  // its pairs of edges would cost more than the whole budget
    PolygonTriangulator triangulator;
    EXPECT_EQ(Triangulate(convex, triangulator).triangles.size(), convex.size() - 2);
    const Split u = Triangulate(kU, triangulator);
    EXPECT_EQ(triangulator.OverBudget(), 0u);
    EXPECT_EQ(triangulator.NoEar(), 0u);
    EXPECT_EQ(u.area, 7.0);
}

TEST(PolygonTriangulation, PastTheBudgetConcavePolygonsAreFanned) {
    PolygonTriangulator triangulator(20);
    const Split first = Triangulate(kU, triangulator);
    EXPECT_EQ(triangulator.OverBudget(), 1u);
    ASSERT_EQ(first.triangles.size(), 6u);
    for (size_t i = 0; i < 6; ++i) EXPECT_EQ(first.triangles[i], glm::uvec3(0, i + 1, i + 2));
    // A convex polygon needs no budget.
    EXPECT_EQ(
        Triangulate({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, triangulator).triangles.size(),
        2u);
    EXPECT_EQ(triangulator.OverBudget(), 1u);
}

TEST(PolygonTriangulation, AConcaveCombOfManyTeeth) {
    // A spine 399 x 1 with 200 teeth 1 wide and 5 tall at x = 2k: area 399 + 1000, and the 199
    // gaps between the teeth stay open.
    std::vector<vec3> comb = {{0, 0, 0}, {399, 0, 0}};
    for (int k = 199; k >= 0; --k) {
        const float x = 2.0f * float(k);
        comb.insert(comb.end(), {{x + 1, 6, 0}, {x, 6, 0}});
        if (k > 0) comb.insert(comb.end(), {{x, 1, 0}, {x - 1, 1, 0}});
    }
    const Split split = Triangulate(comb);
    EXPECT_EQ(split.triangles.size(), comb.size() - 2);
    EXPECT_NEAR(split.area, 1399.0, 1e-6);
    EXPECT_TRUE(split.allAlongNormal);
    for (int gap = 0; gap < 199; ++gap) {
        const float x = 2.0f * float(gap) + 1.0f;
        EXPECT_FALSE(AnyCentroidIn(comb, split.triangles, x, 1.0f, x + 1.0f, 6.0f)) << gap;
    }
}

}  // namespace
}  // namespace rtrt
