#pragma once
// The contact solver's partition of space among its threads: the bodies with a broad-phase box
// cut into kSide x kSide tiles of (nearly) equal counts, across the floor rather than in slabs.
// The solver gives each thread a run of tiles in every colour (ContactBatches' regions), so a body
// moves between cores only when a manifold reaches across a run's border: a run of Morton-ordered
// tiles is a compact patch, whose border holds far fewer bodies than that of a slab of the same
// count (a 32 m floor cut into 16 slabs of 2 m has most of its 0.5 m bodies on a border).
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "engine/physics_anim/broad_phase.h"

namespace rtrt::physics {

class SolverTiles {
  public:
    static constexpr uint32_t kSide = 16;
    static constexpr uint32_t kTiles = kSide * kSide;

    // After sweep.FindPairs(boxes, ...): columns cut the sweep order into kSide equal runs, and
    // each column is cut into kSide equal runs along the axis of the strips (by box centre, ties
    // by sweep rank); tile numbers interleave the column's and row's bits (Morton order). Box i's
    // tile goes to tileOut[to[i]], and its slot, its place when the boxes are laid out tile by
    // tile (each tile along the strip axis), to slotOut[to[i]]. Depends only on the boxes.
    void Assign(std::span<const BroadPhaseBox> boxes, const SweepAndPrune& sweep,
                std::span<const uint32_t> to, std::span<uint8_t> tileOut,
                std::span<uint32_t> slotOut);

    static uint32_t Morton(uint32_t column, uint32_t row);

  private:
    std::vector<std::pair<float, uint32_t>> keys_;  // (centre on the strip axis, sweep rank)
    std::vector<uint32_t> tileStart_;               // each tile's first slot
};

}  // namespace rtrt::physics
