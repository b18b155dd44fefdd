#include "engine/physics_anim/solver_tiles.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace rtrt::physics {

namespace {

// The first of n items in part k of parts equal parts.
uint32_t PartBegin(size_t n, uint32_t k, uint32_t parts) {
    return static_cast<uint32_t>(n * k / parts);
}

}  // namespace

uint32_t SolverTiles::Morton(uint32_t column, uint32_t row) {
    uint32_t code = 0;
    for (uint32_t bit = 0; (1u << bit) < kSide; ++bit) {
        code |= ((column >> bit & 1u) << (2 * bit + 1)) | ((row >> bit & 1u) << (2 * bit));
    }
    return code;
}

void SolverTiles::Assign(std::span<const BroadPhaseBox> boxes, const SweepAndPrune& sweep,
                         std::span<const uint32_t> to, std::span<uint8_t> tileOut,
                         std::span<uint32_t> slotOut) {
    const size_t n = boxes.size();
    const int axis = sweep.CrossAxis();
    // Tile (column, row) holds the items [PartBegin(size, row), PartBegin(size, row + 1)) of
    // its column, of size items.
    const auto rowSize = [&](uint32_t column, uint32_t row) {
        const uint32_t size = PartBegin(n, column + 1, kSide) - PartBegin(n, column, kSide);
        return PartBegin(size, row + 1, kSide) - PartBegin(size, row, kSide);
    };
    tileStart_.assign(kTiles, 0);
    std::vector<uint32_t>& start = tileStart_;
    uint32_t place = 0;
    for (uint32_t tile = 0; tile < kTiles; ++tile) {
        uint32_t column = 0;
        uint32_t row = 0;
        for (uint32_t bit = 0; (1u << bit) < kSide; ++bit) {
            column |= (tile >> (2 * bit + 1) & 1u) << bit;
            row |= (tile >> (2 * bit) & 1u) << bit;
        }
        start[tile] = place;
        place += rowSize(column, row);
    }
    keys_.resize(n);
    tbb::parallel_for(uint32_t{0}, kSide, [&](uint32_t column) {
        const uint32_t begin = PartBegin(n, column, kSide);
        const uint32_t end = PartBegin(n, column + 1, kSide);
        for (uint32_t rank = begin; rank < end; ++rank) {
            const BroadPhaseBox& box = boxes[sweep.BoxAt(rank)];
            const float centre = 0.5f * (box.min[axis] + box.max[axis]);
            // A NaN would break the sort's order; such a box goes last.
            keys_[rank] = {std::isnan(centre) ? HUGE_VALF : centre, rank};
        }
        std::sort(keys_.begin() + begin, keys_.begin() + end);
        const uint32_t size = end - begin;
        for (uint32_t row = 0, p = 0; row < kSide; ++row) {
            const uint32_t tile = Morton(column, row);
            for (uint32_t k = 0; p < PartBegin(size, row + 1, kSide); ++p, ++k) {
                const uint32_t box = sweep.BoxAt(keys_[begin + p].second);
                tileOut[to[box]] = static_cast<uint8_t>(tile);
                slotOut[to[box]] = start[tile] + k;
            }
        }
    });
}

}  // namespace rtrt::physics
