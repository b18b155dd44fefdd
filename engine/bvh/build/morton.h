#pragma once
// 30-bit Morton codes (10 bits per axis) of points normalised to a box: the sort key of the LBVH.
#include "engine/geometry/aabb.h"

namespace rtrt {

// Spreads the low 10 bits of v so that two zero bits separate each (bit i moves to bit 3i).
RT_HD inline uint32_t ExpandBits10(uint32_t v) {
    v &= 0x3ffu;
    v = (v * 0x00010001u) & 0xFF0000FFu;
    v = (v * 0x00000101u) & 0x0F00F00Fu;
    v = (v * 0x00000011u) & 0xC30C30C3u;
    v = (v * 0x00000005u) & 0x49249249u;
    return v;
}

RT_HD inline uint32_t Morton3(uint32_t x, uint32_t y, uint32_t z) {
    return (ExpandBits10(x) << 2) | (ExpandBits10(y) << 1) | ExpandBits10(z);
}

// The Morton code of p inside bounds; an axis along which bounds is flat (or p is NaN) maps to 0,
// so zero-extent scenes get valid (equal) codes.
RT_HD inline uint32_t MortonCode(vec3 p, const Aabb& bounds) {
    uint32_t q[3];
    for (int axis = 0; axis < 3; ++axis) {
        const float extent = bounds.max[axis] - bounds.min[axis];
        float t = extent > 0.0f ? (p[axis] - bounds.min[axis]) / extent : 0.0f;
        t = t >= 0.0f ? t : 0.0f;  // NaN -> 0
        t = t <= 1.0f ? t : 1.0f;
        q[axis] = uint32_t(t * 1023.0f);
    }
    return Morton3(q[0], q[1], q[2]);
}

}  // namespace rtrt
