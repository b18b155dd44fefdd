#pragma once
// Candidate pairs for the narrow phase: axis-aligned boxes that overlap.
#include <atomic>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "engine/core/math.h"

namespace rtrt::physics {

struct BroadPhaseBox {
    vec3 min;
    vec3 max;
    bool isStatic;  // two static boxes never make a pair
};

// Sort and sweep (Baraff 1992, "Dynamic Simulation of Non-Penetrating Rigid Bodies", ch. 7) in
// strips: the boxes sorted by their lower bound on the axis along which their centres spread
// most, and dealt into strips across the axis of the second spread (a box into every strip it
// overlaps); within a strip each box is tested against the following ones until their lower
// bound passes its upper bound. On a floor covered in bodies a plain sweep tests each box against
// every box in its slab across the whole floor; strips cut that to the boxes of its neighbourhood.
// Cost is O(n log n) plus the overlaps on the sweep axis within strips, in parallel on TBB. The
// pairs and their order depend only on the boxes.
class SweepAndPrune {
  public:
    // Replaces pairs with every overlapping (i, j), i < j, that is not static-static; touching
    // boxes (equal bounds) overlap. With names, box i is named names[i] in the pairs instead
    // (names must increase with i, so that the pairs stay in order).
    // With a pair limit (SetPairLimit), stops once the sweep has found more pairs than it
    // allows and returns false, the pairs then incomplete; true otherwise.
    bool FindPairs(std::span<const BroadPhaseBox> boxes,
                   std::vector<std::pair<uint32_t, uint32_t>>& pairs,
                   std::span<const uint32_t> names = {});
    // Bounds the memory and work of FindPairs where boxes packed into one place make pairs of
    // every two: it stops past MAX_PAIRS pairs (give or take one box's pairs).
    void SetPairLimit(size_t maxPairs) { maxPairs_ = maxPairs; }
    // After FindPairs: each box's place in the sweep order, a spatial key (nearby boxes have
    // nearby ranks along the sweep axis).
    void Ranks(std::vector<uint32_t>& rankOfBox) const;
    // The same ranks, each box's written to out[to[box]].
    void Ranks(std::span<const uint32_t> to, std::span<uint32_t> out) const;

  private:
    struct Entry {
        float min;
        uint32_t box;
    };
    // The boxes strip by strip, each strip in sweep order: their bounds on the sweep axis (0),
    // the strip axis (1) and the third (2), apart, so that a box is tested against eight
    // following ones at once (lanes.h). Padded at the end so that eight can always be read.
    struct SweptBoxes {
        std::vector<float> min0, max0, min1, max1, min2, max2;
        std::vector<uint32_t> box;
        std::vector<int32_t> isStatic;  // -1 (all bits, a lane mask) or 0
        void Resize(size_t n);
    };
    // Strips across the strip axis, of equal width from `low`; one strip holds every box.
    struct Strips {
        uint32_t count = 1;
        float low = 0.0f;
        float perUnit = 0.0f;  // strips per unit of length
        uint32_t Of(float x) const {
            const float k = (x - low) * perUnit;
            if (!(k > 0.0f)) return 0;  // NaN too
            return k >= static_cast<float>(count) ? count - 1 : static_cast<uint32_t>(k);
        }
    };
    // low and high: the boxes' bounds on the strip axis.
    Strips PlanStrips(std::span<const BroadPhaseBox> boxes, int stripAxis, float low, float high);
    // Fills sorted_ and stripBegin_ from order_.
    void DealIntoStrips(std::span<const BroadPhaseBox> boxes, const Strips& strips, int axis,
                        int stripAxis, int other2);
    // Appends the pairs of strip's boxes to out, in sweep order.
    void SweepStrip(const Strips& strips, uint32_t strip,
                    std::vector<std::pair<uint32_t, uint32_t>>& out) const;

    std::vector<Entry> order_;  // the sweep order, kept for the next step's sort
    int lastAxis_ = -1;
    std::vector<float> extents_;             // PlanStrips' scratch
    std::vector<uint32_t> stripBegin_;       // each strip's boxes in sorted_
    std::vector<uint32_t> chunkStripCount_;  // DealIntoStrips' scratch
    std::vector<size_t> pairStart_;          // each strip's pairs in the output
    SweptBoxes sorted_;
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> stripPairs_;
    size_t maxPairs_ = SIZE_MAX;
    mutable std::atomic<size_t> found_{0};  // counted only under a limit
};

}  // namespace rtrt::physics
