#pragma once
// Candidate pairs for the narrow phase: axis-aligned boxes that overlap.
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

// Sort and sweep (Baraff 1992, "Dynamic Simulation of Non-Penetrating Rigid Bodies", ch. 7): the
// boxes sorted by their lower bound on the axis along which their centres spread most; each box
// is tested against the following ones until their lower bound passes its upper bound. Cost is
// O(n log n) plus the overlaps on that axis, in parallel on TBB. The order of the pairs depends
// only on the boxes.
class SweepAndPrune {
  public:
    // Replaces pairs with every overlapping (i, j), i < j, that is not static-static; touching
    // boxes (equal bounds) overlap.
    void FindPairs(std::span<const BroadPhaseBox> boxes,
                   std::vector<std::pair<uint32_t, uint32_t>>& pairs);
    // After FindPairs: each box's place in the sweep order, a spatial key (nearby boxes have
    // nearby ranks along the sweep axis).
    void Ranks(std::vector<uint32_t>& rankOfBox) const;

  private:
    struct Entry {
        float min;
        uint32_t box;
    };
    // A box with its bounds on the sweep axis (0) and the two others (1, 2); 32 bytes.
    struct SweptBox {
        float min0, max0, min1, max1, min2, max2;
        uint32_t box;
        uint32_t isStatic;
    };
    static constexpr size_t kSlice = 256;  // boxes per parallel task of the sweep
    std::vector<Entry> order_;
    std::vector<SweptBox> sorted_;  // in sweep order
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> slicePairs_;
};

}  // namespace rtrt::physics
