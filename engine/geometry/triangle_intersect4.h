#pragma once
// Up to four triangles against one ray at once with SSE (host only): the watertight test of
// triangle_intersect.h lane by lane, the same float operations in the same order, so that every
// lane's answer is the scalar test's bit for bit. Lanes the scalar test sends down its rare paths
// (an edge function exactly 0, redone in double; a hit within the error bound of the origin,
// decided on the plane) are handed to the scalar test itself. Like the scalar test it relies on
// host code being compiled with -ffp-contract=off (engine/core): g++ fuses the intrinsics'
// products and sums into FMAs otherwise.
#if defined(__CUDACC__)
#error "triangle_intersect4.h is host code"
#endif
#include <immintrin.h>

#include "engine/geometry/triangle_intersect.h"

namespace rtrt {

struct TriangleHits4 {
    alignas(16) float t[4];
    alignas(16) float b1[4];
    alignas(16) float b2[4];
    int mask;  // bit i: triangle i is hit at t[i] <= tMax
};

namespace triangle4_detail {

inline __m128 AbsPs(__m128 v) { return _mm_andnot_ps(_mm_set1_ps(-0.0f), v); }
// MaxOrKeep lane by lane: maxps returns its second operand unless the first is greater.
inline __m128 MaxOrKeepPs(__m128 candidate, __m128 acc) { return _mm_max_ps(candidate, acc); }

}  // namespace triangle4_detail

// tris[0, count), count 1 to 4, against r within (0, tMax]. Forced inline: g++ left it a call in
// the leaf helpers below, its vectors passed through memory.
[[gnu::always_inline]] inline void IntersectTriangles4(const Triangle* tris, uint32_t count,
                                                       const RaySetup& r, float tMax,
                                                       TriangleHits4* out) {
    using namespace triangle4_detail;
    // Gather the lanes' vertices into one vector per coordinate: floats 0-3 and 4-7 of each
    // triangle transposed, float 8 (v2.z) on its own so that no load reads past a triangle.
    const float* p[4];
    for (uint32_t i = 0; i < 4; ++i) p[i] = &tris[i < count ? i : count - 1].v0.x;
    __m128 a0 = _mm_loadu_ps(p[0]), a1 = _mm_loadu_ps(p[1]);
    __m128 a2 = _mm_loadu_ps(p[2]), a3 = _mm_loadu_ps(p[3]);
    _MM_TRANSPOSE4_PS(a0, a1, a2, a3);  // v0.x, v0.y, v0.z, v1.x
    __m128 c0 = _mm_loadu_ps(p[0] + 4), c1 = _mm_loadu_ps(p[1] + 4);
    __m128 c2 = _mm_loadu_ps(p[2] + 4), c3 = _mm_loadu_ps(p[3] + 4);
    _MM_TRANSPOSE4_PS(c0, c1, c2, c3);  // v1.y, v1.z, v2.x, v2.y
    const __m128 v2z = _mm_setr_ps(p[0][8], p[1][8], p[2][8], p[3][8]);
    const __m128 v0[3] = {a0, a1, a2};
    const __m128 v1[3] = {a3, c0, c1};
    const __m128 v2[3] = {c2, c3, v2z};

    const __m128 zero = _mm_setzero_ps();
    const __m128 ox = _mm_set1_ps(r.originK.x), oy = _mm_set1_ps(r.originK.y);
    const __m128 oz = _mm_set1_ps(r.originK.z);
    const __m128 shearX = _mm_set1_ps(r.shearX), shearY = _mm_set1_ps(r.shearY);
    const __m128 shearZ = _mm_set1_ps(r.shearZ);
    const __m128 aKz = _mm_sub_ps(v0[r.kz], oz), bKz = _mm_sub_ps(v1[r.kz], oz);
    const __m128 cKz = _mm_sub_ps(v2[r.kz], oz);
    const __m128 ax = _mm_sub_ps(_mm_sub_ps(v0[r.kx], ox), _mm_mul_ps(shearX, aKz));
    const __m128 ay = _mm_sub_ps(_mm_sub_ps(v0[r.ky], oy), _mm_mul_ps(shearY, aKz));
    const __m128 bx = _mm_sub_ps(_mm_sub_ps(v1[r.kx], ox), _mm_mul_ps(shearX, bKz));
    const __m128 by = _mm_sub_ps(_mm_sub_ps(v1[r.ky], oy), _mm_mul_ps(shearY, bKz));
    const __m128 cx = _mm_sub_ps(_mm_sub_ps(v2[r.kx], ox), _mm_mul_ps(shearX, cKz));
    const __m128 cy = _mm_sub_ps(_mm_sub_ps(v2[r.ky], oy), _mm_mul_ps(shearY, cKz));
    const __m128 u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
    const __m128 v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
    const __m128 w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
    const __m128 edgeZero =
        _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)), _mm_cmpeq_ps(w, zero));
    const __m128 anyNegative =
        _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u, zero), _mm_cmplt_ps(v, zero)), _mm_cmplt_ps(w, zero));
    const __m128 anyPositive =
        _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u, zero), _mm_cmpgt_ps(v, zero)), _mm_cmpgt_ps(w, zero));
    const __m128 outside = _mm_and_ps(anyNegative, anyPositive);
    const __m128 det = _mm_add_ps(_mm_add_ps(u, v), w);
    const __m128 az = _mm_mul_ps(shearZ, aKz), bz = _mm_mul_ps(shearZ, bKz);
    const __m128 cz = _mm_mul_ps(shearZ, cKz);
    const __m128 t =
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(u, az), _mm_mul_ps(v, bz)), _mm_mul_ps(w, cz));
    // The error bound of t times |det|, as the scalar test computes it.
    const __m128 maxZt = MaxOrKeepPs(AbsPs(az), MaxOrKeepPs(AbsPs(bz), AbsPs(cz)));
    const __m128 maxXt = MaxOrKeepPs(AbsPs(ax), MaxOrKeepPs(AbsPs(bx), AbsPs(cx)));
    const __m128 maxYt = MaxOrKeepPs(AbsPs(ay), MaxOrKeepPs(AbsPs(by), AbsPs(cy)));
    const __m128 deltaZ = _mm_mul_ps(_mm_set1_ps(Gamma(3)), maxZt);
    const __m128 maxZ = MaxOrKeepPs(AbsPs(aKz), MaxOrKeepPs(AbsPs(bKz), AbsPs(cKz)));
    const __m128 gamma5 = _mm_set1_ps(Gamma(5));
    const __m128 deltaX = _mm_mul_ps(gamma5, _mm_add_ps(maxXt, maxZ));
    const __m128 deltaY = _mm_mul_ps(gamma5, _mm_add_ps(maxYt, maxZ));
    const __m128 deltaE = _mm_mul_ps(
        _mm_set1_ps(2.0f),
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(_mm_set1_ps(Gamma(2)), maxXt), maxYt),
                              _mm_mul_ps(deltaY, maxXt)),
                   _mm_mul_ps(deltaX, maxYt)));
    const __m128 maxE = MaxOrKeepPs(AbsPs(u), MaxOrKeepPs(AbsPs(v), AbsPs(w)));
    const __m128 deltaTimesDet =
        _mm_mul_ps(_mm_set1_ps(3.0f),
                   _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(_mm_set1_ps(Gamma(3)), maxE), maxZt),
                                         _mm_mul_ps(deltaE, maxZt)),
                              _mm_mul_ps(deltaZ, maxE)));
    const __m128 signBit = _mm_set1_ps(-0.0f);
    const __m128 tSigned = _mm_xor_ps(t, _mm_and_ps(_mm_cmplt_ps(det, zero), signBit));
    const __m128 absDet = AbsPs(det);
    const __m128 invDet = _mm_div_ps(_mm_set1_ps(1.0f), det);
    const __m128 tMaxV = _mm_set1_ps(tMax);
    const __m128 beyondBound = _mm_cmpgt_ps(tSigned, deltaTimesDet);
    const __m128 beyondTMax = _mm_cmpgt_ps(
        tSigned, _mm_mul_ps(_mm_mul_ps(tMaxV, absDet), _mm_set1_ps(1.0f + 2.0f * Gamma(3))));
    const __m128 tHit = _mm_mul_ps(t, invDet);
    const __m128 inBand =
        _mm_andnot_ps(beyondBound, _mm_cmpge_ps(tSigned, _mm_xor_ps(deltaTimesDet, signBit)));
    const __m128 candidate = _mm_andnot_ps(_mm_or_ps(outside, _mm_cmpeq_ps(det, zero)),
                                           _mm_castsi128_ps(_mm_set1_epi32(-1)));
    const __m128 hit = _mm_and_ps(_mm_and_ps(candidate, beyondBound),
                                  _mm_andnot_ps(beyondTMax, _mm_cmple_ps(tHit, tMaxV)));
    const int lanes = (1 << count) - 1;
    const int scalar =
        (_mm_movemask_ps(edgeZero) | _mm_movemask_ps(_mm_and_ps(candidate, inBand))) & lanes;
    _mm_store_ps(out->t, tHit);
    _mm_store_ps(out->b1, _mm_mul_ps(v, invDet));
    _mm_store_ps(out->b2, _mm_mul_ps(w, invDet));
    out->mask = _mm_movemask_ps(hit) & lanes & ~scalar;
    for (int rest = scalar; rest != 0; rest &= rest - 1) {
        const int i = __builtin_ctz(rest);
        TriangleHit h;
        if (!IntersectTriangle(tris[i], r, tMax, &h)) continue;
        out->t[i] = h.t;
        out->b1[i] = h.b1;
        out->b2[i] = h.b2;
        out->mask |= 1 << i;
    }
}

// The closest hit among tris[0, count) within tMax, as the scalar test over them in order finds
// it (of hits at equal t, the later triangle's): its index, or -1; tMax lowers to its t. A lone
// triangle goes to the scalar test, which needs no gather.
inline int ClosestTriangle(const Triangle* tris, uint32_t count, const RaySetup& r, float& tMax,
                           TriangleHit* hit) {
    if (count == 1) {
        if (!IntersectTriangle(tris[0], r, tMax, hit)) return -1;
        tMax = hit->t;
        return 0;
    }
    int best = -1;
    for (uint32_t first = 0; first < count; first += 4) {
        const uint32_t n = count - first < 4 ? count - first : 4;
        TriangleHits4 h;
        IntersectTriangles4(tris + first, n, r, tMax, &h);
        bool lowered = false;  // tMax lowered by an earlier lane of this group
        for (int rest = h.mask; rest != 0; rest &= rest - 1) {
            const int i = __builtin_ctz(rest);
            TriangleHit lane{h.t[i], h.b1[i], h.b2[i]};
            // The lanes were tested against the group's first tMax. Against a lower one the
            // scalar test's answer is not always "t <= tMax": its early exit can reject a hit
            // at its own t when that t is subnormal. A second hit in a group (rare) is asked
            // again, so that the leaf's answer is the scalar loop's in every case.
            if (lowered && !IntersectTriangle(tris[first + uint32_t(i)], r, tMax, &lane)) continue;
            tMax = lane.t;
            *hit = lane;
            best = int(first) + i;
            lowered = true;
        }
    }
    return best;
}

// Whether any of tris[0, count) is hit within tMax.
inline bool AnyTriangle(const Triangle* tris, uint32_t count, const RaySetup& r, float tMax) {
    if (count == 1) {
        TriangleHit h;
        return IntersectTriangle(tris[0], r, tMax, &h);
    }
    for (uint32_t first = 0; first < count; first += 4) {
        TriangleHits4 h;
        IntersectTriangles4(tris + first, count - first < 4 ? count - first : 4, r, tMax, &h);
        if (h.mask != 0) return true;
    }
    return false;
}

}  // namespace rtrt
