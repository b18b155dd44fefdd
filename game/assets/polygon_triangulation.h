#pragma once
// The triangles of a polygon face of four or more corners (OBJ and PLY faces).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/core/math.h"

namespace rtrt {

// Splits the polygons of one file. A convex polygon is a fan from its first corner; a concave
// one is ear-clipped in the plane of its Newell normal, so that no triangle covers one of its
// notches, after it is cut into loops where it touches itself at a corner. Ear clipping tests
// candidate ears against the polygon's reflex corners, quadratic in its corners at worst: a file's
// polygons share a budget of such tests, after which the rest are fanned too (counted in
// OverBudget), so that a crafted file of huge concave polygons still loads in seconds. One whose
// edges cross (a bowtie, a star) is fanned and counted in NoEar; the pairwise edge test for that
// has a budget of its own, and convex-turning polygons take a linear test instead.
class PolygonTriangulator {
  public:
    // BUDGET: ear-in-corner tests for the whole file, about a second's worth by default.
    explicit PolygonTriangulator(uint64_t budget = uint64_t{1} << 28)
        : budget_(budget), crossingBudget_(budget) {}

    // Appends the triangles of the polygon whose corners lie at CORNERS, in order, as indices
    // into CORNERS in the polygon's winding. Consecutive corners at the same position count as
    // one; triangles of zero area may result, as from a fan.
    void Triangulate(std::span<const vec3> corners, std::vector<glm::uvec3>& triangles);

    // Polygons that had to be fanned: ones whose edges cross or that fold over themselves (no ear
    // left to clip), and concave ones past the budget.
    uint64_t NoEar() const { return noEar_; }
    uint64_t OverBudget() const { return overBudget_; }

  private:
    enum class Outcome { kDone, kNoEar, kOverBudget };
    bool TurnsMoreThanOnce() const;
    bool CrossesItself();
    bool SplitAtTouchingCorners();
    Outcome ClipEars(std::span<const uint32_t> loop, std::vector<glm::uvec3>& triangles);
    void FanAfterGivingUp(std::vector<glm::uvec3>& triangles, size_t firstTriangle,
                          uint64_t& counter);
    double LoopArea(std::span<const uint32_t> loop) const;
    bool Spend(uint64_t work);  // false, and nothing left, when the budget cannot pay

    uint64_t budget_;
    uint64_t crossingBudget_;  // edge-pair tests of the crossing check, apart from the ears'
    uint64_t noEar_ = 0, overBudget_ = 0;
    // The polygon being split: its distinct corners projected on its plane, oriented so that it
    // winds counter-clockwise, its loops (split where it touches itself) and the ring of a
    // loop's corners not clipped yet.
    std::vector<glm::dvec2> points_;
    std::vector<uint32_t> source_, prev_, next_;
    std::vector<std::vector<uint32_t>> loops_;
};

}  // namespace rtrt
