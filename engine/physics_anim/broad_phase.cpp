#include "engine/physics_anim/broad_phase.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>

namespace rtrt::physics {

namespace {

// The axis with the largest variance of box centres (computed in double: many boxes far from the
// origin would lose the variance to cancellation in float).
int SweepAxis(std::span<const BroadPhaseBox> boxes) {
    double sum[3] = {0.0, 0.0, 0.0};
    double sumSquares[3] = {0.0, 0.0, 0.0};
    for (const BroadPhaseBox& box : boxes) {
        for (int k = 0; k < 3; ++k) {
            const double c = 0.5 * (static_cast<double>(box.min[k]) + box.max[k]);
            sum[k] += c;
            sumSquares[k] += c * c;
        }
    }
    int best = 0;
    double bestVariance = -1.0;
    const auto n = static_cast<double>(boxes.size());
    for (int k = 0; k < 3; ++k) {
        const double variance = sumSquares[k] / n - (sum[k] / n) * (sum[k] / n);
        if (variance > bestVariance) {
            bestVariance = variance;
            best = k;
        }
    }
    return best;
}

}  // namespace

void SweepAndPrune::FindPairs(std::span<const BroadPhaseBox> boxes,
                              std::vector<std::pair<uint32_t, uint32_t>>& pairs) {
    pairs.clear();
    if (boxes.size() < 2) {
        order_.assign(boxes.size(), {0.0f, 0});
        return;
    }
    const int axis = SweepAxis(boxes);
    const int other1 = (axis + 1) % 3;
    const int other2 = (axis + 2) % 3;
    order_.resize(boxes.size());
    for (uint32_t i = 0; i < boxes.size(); ++i) order_[i] = {boxes[i].min[axis], i};
    // Ties broken by index, so the order (and the pairs' order) never depends on the sort.
    tbb::parallel_sort(order_.begin(), order_.end(), [](const Entry& a, const Entry& b) {
        return a.min != b.min ? a.min < b.min : a.box < b.box;
    });
    // The inner loop reads the boxes in sweep order, with the sweep axis first: copied so, they
    // are read sequentially and at fixed offsets.
    sorted_.resize(boxes.size());
    for (size_t i = 0; i < order_.size(); ++i) {
        const BroadPhaseBox& box = boxes[order_[i].box];
        sorted_[i] = {box.min[axis],   box.max[axis],   box.min[other1], box.max[other1],
                      box.min[other2], box.max[other2], order_[i].box,   box.isStatic};
    }
    // Fixed slices of the sweep, each with its own pairs, joined in slice order: the same pairs in
    // the same order as one serial sweep, on any number of threads.
    const size_t slices = (sorted_.size() + kSlice - 1) / kSlice;
    if (slicePairs_.size() < slices) slicePairs_.resize(slices);
    tbb::parallel_for(size_t{0}, slices, [&](size_t slice) {
        std::vector<std::pair<uint32_t, uint32_t>>& out = slicePairs_[slice];
        out.clear();
        const size_t end = std::min(sorted_.size(), (slice + 1) * kSlice);
        for (size_t i = slice * kSlice; i < end; ++i) {
            const SweptBox& a = sorted_[i];
            for (size_t j = i + 1; j < sorted_.size() && sorted_[j].min0 <= a.max0; ++j) {
                const SweptBox& b = sorted_[j];
                const bool overlap = a.min1 <= b.max1 && b.min1 <= a.max1 && a.min2 <= b.max2 &&
                                     b.min2 <= a.max2 && !(a.isStatic && b.isStatic);
                if (overlap) out.emplace_back(std::min(a.box, b.box), std::max(a.box, b.box));
            }
        }
    });
    for (size_t slice = 0; slice < slices; ++slice) {
        pairs.insert(pairs.end(), slicePairs_[slice].begin(), slicePairs_[slice].end());
    }
}

void SweepAndPrune::Ranks(std::vector<uint32_t>& rankOfBox) const {
    rankOfBox.resize(order_.size());
    for (uint32_t rank = 0; rank < order_.size(); ++rank) rankOfBox[order_[rank].box] = rank;
}

}  // namespace rtrt::physics
