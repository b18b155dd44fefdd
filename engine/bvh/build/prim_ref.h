#pragma once
// The builder's working copy of one primitive: its box and its input index in 32 bytes. The
// builder partitions these records themselves, so binning reads memory in order instead of
// chasing an index into the input. Host only (SSE).
#include <immintrin.h>

#include "engine/geometry/aabb.h"

namespace rtrt {

struct alignas(32) PrimRef {
    vec3 lo;
    uint32_t id;
    vec3 hi;
    uint32_t pad;

    PrimRef() = default;
    PrimRef(const Aabb& box, uint32_t index) : lo(box.min), id(index), hi(box.max), pad(0) {}

    Aabb Box() const { return {lo, hi}; }
    // The arithmetic of Aabb::Centroid, so every builder sees the same centroids.
    float Centroid(int axis) const { return 0.5f * (lo[axis] + hi[axis]); }
    // The box corners in lanes 0-2; lane 3 (the id's bits) is zeroed so that it never feeds
    // denormal arithmetic.
    __m128 Lo() const { return _mm_and_ps(_mm_load_ps(&lo.x), XyzMask()); }
    __m128 Hi() const { return _mm_and_ps(_mm_load_ps(&hi.x), XyzMask()); }

    static __m128 XyzMask() { return _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1)); }
};
static_assert(sizeof(PrimRef) == 32);

// Min and max in the operand order of glm::min(acc, x) and glm::max(acc, x) (Aabb::Grow), so
// that SSE and scalar bounds agree bit for bit, signed zeros included.
inline __m128 GrowMin(__m128 acc, __m128 x) { return _mm_min_ps(x, acc); }
inline __m128 GrowMax(__m128 acc, __m128 x) { return _mm_max_ps(x, acc); }

inline vec3 Xyz(__m128 v) {
    alignas(16) float f[4];
    _mm_store_ps(f, v);
    return {f[0], f[1], f[2]};
}

// Bounds of the boxes and of the centroids of a range of records.
struct RangeBounds {
    __m128 boxLo = _mm_set1_ps(kInfinity), boxHi = _mm_set1_ps(-kInfinity);
    __m128 centroidLo = _mm_set1_ps(kInfinity), centroidHi = _mm_set1_ps(-kInfinity);

    void Grow(const RangeBounds& b) {
        boxLo = GrowMin(boxLo, b.boxLo);
        boxHi = GrowMax(boxHi, b.boxHi);
        centroidLo = GrowMin(centroidLo, b.centroidLo);
        centroidHi = GrowMax(centroidHi, b.centroidHi);
    }
    Aabb Boxes() const { return {Xyz(boxLo), Xyz(boxHi)}; }
    Aabb Centroids() const { return {Xyz(centroidLo), Xyz(centroidHi)}; }
};

inline RangeBounds BoundRefs(const PrimRef* refs, uint32_t begin, uint32_t end) {
    RangeBounds r;
    const __m128 half = _mm_set1_ps(0.5f);
    for (uint32_t i = begin; i < end; ++i) {
        const __m128 lo = refs[i].Lo(), hi = refs[i].Hi();
        const __m128 c = _mm_mul_ps(_mm_add_ps(lo, hi), half);
        r.boxLo = GrowMin(r.boxLo, lo);
        r.boxHi = GrowMax(r.boxHi, hi);
        r.centroidLo = GrowMin(r.centroidLo, c);
        r.centroidHi = GrowMax(r.centroidHi, c);
    }
    return r;
}

}  // namespace rtrt
