#pragma once
// A box kept as integer keys that order as the floats they encode, so that a GPU reduction takes
// its minimum and maximum with atomicMin: exact in any order and with no scratch per block. The
// box equals the CPU's serial Aabb::Grow but for the sign of a zero bound (here -0 is below +0;
// Grow keeps the zero it saw first), which no Morton code can tell apart. NaN coordinates are
// skipped, as Grow skips them.
#include "engine/core/float_bounds.h"
#include "engine/geometry/aabb.h"

namespace rtrt {

// Negative floats have their bits flipped, others their sign bit set: unsigned order = float
// order (-0 just below +0).
RT_HD inline uint32_t OrderedKey(float f) {
    const uint32_t u = FloatToBits(f);
    return (u & 0x80000000u) != 0 ? ~u : u | 0x80000000u;
}
RT_HD inline float FromOrderedKey(uint32_t key) {
    return BitsToFloat((key & 0x80000000u) != 0 ? key & 0x7fffffffu : ~key);
}

struct OrderedBounds {
    // Every byte 0xff (one memset): no point yet, which reads back as the empty Aabb.
    static constexpr uint32_t kNone = 0xffffffffu;

    uint32_t minKey[3];     // OrderedKey(min)
    uint32_t negMaxKey[3];  // ~OrderedKey(max): the maximum is the minimum of these

    // The keys point p offers to the reduction; NaN offers kNone.
    RT_HD static uint32_t MinKey(float v) { return v == v ? OrderedKey(v) : kNone; }
    RT_HD static uint32_t NegMaxKey(float v) { return v == v ? ~OrderedKey(v) : kNone; }

    RT_HD operator Aabb() const {
        Aabb box;
        for (int a = 0; a < 3; ++a) {
            if (minKey[a] != kNone) box.min[a] = FromOrderedKey(minKey[a]);
            if (negMaxKey[a] != kNone) box.max[a] = FromOrderedKey(~negMaxKey[a]);
        }
        return box;
    }
};

}  // namespace rtrt
