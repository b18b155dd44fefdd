#include "engine/physics_anim/contact_coloring.h"

#include <bit>

namespace rtrt::physics {

void ContactColoring::Reset(uint32_t bodyCount) { used_.assign(bodyCount, 0); }

uint32_t ContactColoring::Assign(uint32_t a, bool aMoves, uint32_t b, bool bMoves) {
    const uint64_t taken = (aMoves ? used_[a] : 0) | (bMoves ? used_[b] : 0);
    if (taken == ~uint64_t{0}) return kOverflow;
    const auto color = static_cast<uint32_t>(std::countr_one(taken));
    const uint64_t bit = uint64_t{1} << color;
    if (aMoves) used_[a] |= bit;
    if (bMoves) used_[b] |= bit;
    return color;
}

}  // namespace rtrt::physics
