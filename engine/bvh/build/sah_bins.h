#pragma once
// Bins of the binned SAH builder (Wald 2007, "On fast Construction of SAH-based Bounding Volume
// Hierarchies"): per axis, the union box and the count of the primitives whose centroid falls in
// each of binCount equal slices of the centroid bounds. Host only (SSE).
#include <algorithm>
#include <bit>

#include "engine/bvh/build/prim_ref.h"

namespace rtrt {

inline constexpr uint32_t kMaxSahBins = 64;

// Centroid -> bin index on all three axes at once. Binning and partitioning both call Bins, so
// they never disagree about a primitive.
class BinMapping {
  public:
    BinMapping(const Aabb& centroidBounds, uint32_t binCount) : last_(int(binCount) - 1) {
        alignas(16) float lo[4] = {0, 0, 0, 0}, scale[4] = {0, 0, 0, 0};
        for (int a = 0; a < 3; ++a) {
            splittable_[a] = centroidBounds.max[a] > centroidBounds.min[a];
            lo[a] = centroidBounds.min[a];
            if (splittable_[a]) scale[a] = float(binCount) / (centroidBounds.max[a] - lo[a]);
        }
        lo_ = _mm_load_ps(lo);
        scale_ = _mm_load_ps(scale);
    }

    bool Splittable(int axis) const { return splittable_[axis]; }

    // Bin of each axis in bins[0..2]; NaN or out-of-range positions clamp into [0, binCount).
    void Bins(__m128 lo, __m128 hi, int bins[4]) const {
        const __m128 c = _mm_mul_ps(_mm_add_ps(lo, hi), _mm_set1_ps(0.5f));
        const __m128i i = _mm_cvttps_epi32(_mm_mul_ps(_mm_sub_ps(c, lo_), scale_));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(bins), i);
        for (int a = 0; a < 3; ++a) bins[a] = std::clamp(bins[a], 0, last_);
    }
    uint32_t Bin(const PrimRef& r, int axis) const {
        int bins[4];
        Bins(r.Lo(), r.Hi(), bins);
        return uint32_t(bins[axis]);
    }

  private:
    __m128 lo_, scale_;
    int last_;
    bool splittable_[3];
};

// Only the bins primitives fall into are touched: a bit mask per axis says which hold anything,
// so that the many small nodes near the leaves pay for their primitives, not for binCount.
class SahBins {
  public:
    void Add(const PrimRef* first, const PrimRef* last, const BinMapping& mapping) {
        for (const PrimRef* r = first; r != last; ++r) {
            const __m128 lo = r->Lo(), hi = r->Hi();
            int bins[4];
            mapping.Bins(lo, hi, bins);
            for (int a = 0; a < 3; ++a) Put(a, uint32_t(bins[a]), lo, hi, 1);
        }
    }

    void Merge(const SahBins& o) {
        for (int a = 0; a < 3; ++a)
            for (uint64_t bits = o.used_[a]; bits != 0; bits &= bits - 1) {
                const uint32_t b = uint32_t(std::countr_zero(bits));
                Put(a, b, o.lo_[a][b], o.hi_[a][b], o.count_[a][b]);
            }
    }

    // The cheapest plane over all axes (cost: sum of N * area of both sides) among those with
    // primitives on both sides; axis -1 when there is none. Only planes right after a non-empty
    // bin are evaluated: a plane after an empty bin splits like the one before it at the same
    // cost, and ties keep the lowest bin, so the answer is the full scan's.
    struct Plane {
        int axis = -1;
        uint32_t bin = 0;  // first bin of the right side
        float cost = kInfinity;
    };
    Plane BestPlane(const BinMapping& mapping) const {
        Plane best;
        for (int axis = 0; axis < 3; ++axis) {
            if (!mapping.Splittable(axis)) continue;
            uint32_t used[kMaxSahBins];
            uint32_t usedCount = 0;
            for (uint64_t bits = used_[axis]; bits != 0; bits &= bits - 1)
                used[usedCount++] = uint32_t(std::countr_zero(bits));
            if (usedCount < 2) continue;
            float rightCost[kMaxSahBins];
            __m128 lo = _mm_set1_ps(kInfinity), hi = _mm_set1_ps(-kInfinity);
            uint32_t n = 0;
            for (uint32_t j = usedCount - 1; j > 0; --j) {
                const uint32_t b = used[j];
                lo = GrowMin(lo, lo_[axis][b]);
                hi = GrowMax(hi, hi_[axis][b]);
                n += count_[axis][b];
                rightCost[j] = float(n) * Area(lo, hi);
            }
            lo = _mm_set1_ps(kInfinity);
            hi = _mm_set1_ps(-kInfinity);
            n = 0;
            for (uint32_t j = 0; j + 1 < usedCount; ++j) {
                const uint32_t b = used[j];
                lo = GrowMin(lo, lo_[axis][b]);
                hi = GrowMax(hi, hi_[axis][b]);
                n += count_[axis][b];
                const float cost = float(n) * Area(lo, hi) + rightCost[j + 1];
                if (cost < best.cost) best = {axis, b + 1, cost};
            }
        }
        return best;
    }

  private:
    // A bin's first primitive sets its box (what growing the empty box would give); later ones
    // grow it.
    void Put(int a, uint32_t b, __m128 lo, __m128 hi, uint32_t count) {
        const uint64_t bit = uint64_t(1) << b;
        if (used_[a] & bit) {
            lo_[a][b] = GrowMin(lo_[a][b], lo);
            hi_[a][b] = GrowMax(hi_[a][b], hi);
            count_[a][b] += count;
        } else {
            used_[a] |= bit;
            lo_[a][b] = lo;
            hi_[a][b] = hi;
            count_[a][b] = count;
        }
    }

    // Aabb::Area's arithmetic, in its order, for a non-empty box.
    static float Area(__m128 lo, __m128 hi) {
        const __m128 e = _mm_sub_ps(hi, lo);
        alignas(16) float p[4];
        _mm_store_ps(p, _mm_mul_ps(e, _mm_shuffle_ps(e, e, _MM_SHUFFLE(3, 0, 2, 1))));
        return 2.0f * (p[0] + p[1] + p[2]);
    }

    uint64_t used_[3] = {0, 0, 0};  // bit b: bin b holds primitives
    __m128 lo_[3][kMaxSahBins], hi_[3][kMaxSahBins];
    uint32_t count_[3][kMaxSahBins];
};

}  // namespace rtrt
