#pragma once
// Host-only traversal of the 4-wide BVH (bvh4.h): one SSE slab test for four children, nearest
// child first, farther hits on a stack with their entry distance so that entries already beyond
// the closest hit are dropped. Same slab semantics as slab_test.h (inclusive, NaN lanes dropped,
// far distance widened by 1 + 2 gamma(3)); leaves use the same primitive tests.
#if defined(__CUDACC__)
#error "bvh4_traversal.h is host code; the CUDA back end traverses the binary BVH"
#endif
#include <immintrin.h>

#include <type_traits>

#include "engine/bvh/layout/bvh4.h"
#include "engine/bvh/traversal/traversal.h"
#include "engine/geometry/ray_setup.h"

namespace rtrt {

struct WideRay {
    __m128 origin[3], invDir[3];
    uint32_t nearOffset[3], farOffset[3];  // byte offsets of the near/far plane arrays per axis
};

inline WideRay MakeWideRay(const RaySetup& r) {
    WideRay w;
    for (int a = 0; a < 3; ++a) {
        w.origin[a] = _mm_set1_ps(r.origin[a]);
        w.invDir[a] = _mm_set1_ps(r.invDir[a]);
        const bool negative = r.nearOffset[a] >= 4;
        w.nearOffset[a] = (negative ? kBvh4MaxOffset : kBvh4MinOffset) + 16u * uint32_t(a);
        w.farOffset[a] = (negative ? kBvh4MinOffset : kBvh4MaxOffset) + 16u * uint32_t(a);
    }
    return w;
}

// Bit i set when the ray enters child i's box before tMax; entry distances in tEntry.
inline int SlabTest4(const Bvh4Node& node, const WideRay& r, float tMax, __m128* tEntry) {
    const char* base = reinterpret_cast<const char*>(&node);
    __m128 t0 = _mm_setzero_ps();
    __m128 t1 = _mm_set1_ps(tMax);
    for (int a = 0; a < 3; ++a) {
        const __m128 nearPlane =
            _mm_load_ps(reinterpret_cast<const float*>(base + r.nearOffset[a]));
        const __m128 farPlane = _mm_load_ps(reinterpret_cast<const float*>(base + r.farOffset[a]));
        // _mm_max_ps / _mm_min_ps return the second operand when either is NaN: the accumulator.
        t0 = _mm_max_ps(_mm_mul_ps(_mm_sub_ps(nearPlane, r.origin[a]), r.invDir[a]), t0);
        t1 = _mm_min_ps(_mm_mul_ps(_mm_sub_ps(farPlane, r.origin[a]), r.invDir[a]), t1);
    }
    *tEntry = t0;
    const __m128 widened = _mm_mul_ps(t1, _mm_set1_ps(1.0f + 2.0f * Gamma(3)));
    return _mm_movemask_ps(_mm_cmple_ps(t0, widened));
}

inline constexpr uint32_t kBvh4StackSize = 3 * kBvhStackSize + 4;

// Both queries, as Traverse in traversal.h: test(slot, tMax) tests one primitive, or
// test(first, count, tMax) a whole leaf; kOccluded stops at the first that blocks the ray and,
// with tMax fixed, neither sorts children nor prunes pops.
template <Query kQuery, typename TestPrim>
inline bool Traverse4(const Bvh4Node* nodes, const RaySetup& ray, float& tMax, TestPrim&& test) {
    struct Entry {
        uint32_t child, count;
        float tEntry;
    };
    Entry stack[kBvh4StackSize];
    uint32_t stackSize = 0;
    const WideRay wide = MakeWideRay(ray);
    bool found = false;
    Entry current{0, 0, 0.0f};
    for (;;) {
        if (current.count > 0) {
            if constexpr (std::is_invocable_v<TestPrim&, uint32_t, uint32_t, float&>) {
                // A test of the whole leaf, test(first, count, tMax).
                if (test(current.child, current.count, tMax)) {
                    if constexpr (kQuery == Query::kOccluded) return true;
                    found = true;
                }
            } else {
                for (uint32_t i = 0; i < current.count; ++i) {
                    if (test(current.child + i, tMax)) {
                        if constexpr (kQuery == Query::kOccluded) return true;
                        found = true;
                    }
                }
            }
        } else {
            const Bvh4Node& node = nodes[current.child];
            __m128 tEntry;
            int mask = SlabTest4(node, wide, tMax, &tEntry);
            alignas(16) float t[4];
            _mm_store_ps(t, tEntry);
            // Collect the hit children, then visit the last and stack the rest; kIntersect sorts
            // them far to near first, so that the nearest is visited first.
            Entry hits[4];
            int hitCount = 0;
            while (mask) {
                const int i = __builtin_ctz(mask);
                mask &= mask - 1;
                Entry e{node.child[i], node.count[i], t[i]};
                int j = hitCount++;
                if constexpr (kQuery == Query::kIntersect)
                    for (; j > 0 && hits[j - 1].tEntry < e.tEntry; --j) hits[j] = hits[j - 1];
                hits[j] = e;
            }
            if (hitCount > 0) {
                for (int i = 0; i < hitCount - 1; ++i) stack[stackSize++] = hits[i];
                current = hits[hitCount - 1];
                continue;
            }
        }
        // Pop, skipping entries the closest hit so far already lies before. The entry distance
        // is rounded like the slab test's, so it gets the slab test's widening: a triangle lying
        // in a box face can have t one ulp below the box's computed entry, and an unwidened
        // compare dropped such boxes and returned a farther hit (tests/robust, traversal).
        for (;;) {
            if (stackSize == 0) return found;
            current = stack[--stackSize];
            if (kQuery == Query::kOccluded || current.tEntry <= tMax * (1.0f + 2.0f * Gamma(3)))
                break;
        }
    }
}

}  // namespace rtrt
