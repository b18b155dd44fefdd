#pragma once
// Traversal of the compressed 8-wide BVH (wide_bvh.h) in portable code: the GPU's BLAS loop for
// triangle BLASes in the nested form, run on the CPU by the tests.
//
// A node is five 16-byte loads. Its children's boxes are tested with one fused multiply-add per
// plane and the semantics of slab_test.h (inclusive, NaN lanes dropped, far distance widened by
// 1 + 2 gamma(3)), on boxes widened for the rounding of the per-node terms, so a child is entered
// whenever the binary tree would enter it. The hit children become two 8-bit
// masks in visiting order (bit k for slot k ^ octant): the leaves are tested at once, the nearest
// interior child is visited next and the rest wait on the stack as one entry (the node's
// childBase and the remaining bits), as in Ylitie et al. (2017). Entries are not re-tested when
// popped: their boxes were hit at the time.
#include "engine/bvh/layout/wide_bvh.h"
#include "engine/bvh/traversal/traversal.h"
#include "engine/geometry/ray_setup.h"

#if !defined(__CUDA_ARCH__)
#include <bit>
#endif

namespace rtrt {

RT_HD inline uint32_t LowestBit(uint32_t v) {
#if defined(__CUDA_ARCH__)
    return uint32_t(__ffs(int(v)) - 1);
#else
    return uint32_t(std::countr_zero(v));
#endif
}

RT_HD inline uint32_t BitCount(uint32_t v) {
#if defined(__CUDA_ARCH__)
    return uint32_t(__popc(v));
#else
    return uint32_t(std::popcount(v));
#endif
}

// The node as twenty 32-bit words (layout of WideBvhNode), loaded once.
struct WideNodeWords {
    uint32_t w[20];
};

RT_HD inline WideNodeWords LoadWideNode(const WideBvhNode* node) {
    WideNodeWords words;
#if defined(__CUDA_ARCH__)
    const uint4* p = reinterpret_cast<const uint4*>(node);
#pragma unroll
    for (int i = 0; i < 5; ++i) {
        const uint4 v = __ldg(p + i);
        words.w[4 * i] = v.x;
        words.w[4 * i + 1] = v.y;
        words.w[4 * i + 2] = v.z;
        words.w[4 * i + 3] = v.w;
    }
#else
    std::memcpy(words.w, node, sizeof(words.w));
#endif
    return words;
}

RT_HD inline float WordAsFloat(uint32_t w) {
#if defined(__CUDA_ARCH__)
    return __uint_as_float(w);
#else
    float f;
    std::memcpy(&f, &w, sizeof(f));
    return f;
#endif
}

// Byte k of a word as the float 2^23 + byte: the byte in the low mantissa bits of 2^23, one byte
// permute on the GPU instead of an integer conversion.
RT_HD inline float WideBiasedByte(uint32_t word, uint32_t k) {
#if defined(__CUDA_ARCH__)
    return __uint_as_float(__byte_perm(word, 0x4b00u, 0x5440u | k));
#else
    return WordAsFloat(0x4b000000u | ((word >> (8u * k)) & 0xffu));
#endif
}

// Word offsets inside WideNodeWords.
inline constexpr int kWideMetaWord = 3;  // exponents (3 bytes), interiorMask
inline constexpr int kWideChildBaseWord = 4;
inline constexpr int kWideLeafBaseWord = 5;
inline constexpr int kWideLeafMaskWord = 6;
inline constexpr int kWideQloWord = 8;   // qlo[a][s]: byte s % 4 of word 8 + 2a + s / 4
inline constexpr int kWideQhiWord = 14;  // qhi likewise from word 14

// Bit k of hits names slot k ^ octant; the interior child at that slot.
RT_HD inline uint32_t WideChildIndex(uint32_t childBase, uint32_t interiorMask, uint32_t slot) {
    return childBase + BitCount(interiorMask & ((1u << slot) - 1u));
}

// Both queries, as Traverse in traversal.h: test(slot, tMax) tests one primitive of the binary
// BVH's leaf order.
template <Query kQuery, typename TestPrim>
RT_HD inline bool TraverseWide(const WideBvhNode* nodes, const WideBvhLeaf* leaves,
                               const RaySetup& ray, float& tMax, TestPrim&& test) {
    const bool negative[3] = {ray.invDir.x < 0.0f, ray.invDir.y < 0.0f, ray.invDir.z < 0.0f};
    const uint32_t octant =
        (negative[0] ? 1u : 0u) | (negative[1] ? 2u : 0u) | (negative[2] ? 4u : 0u);
    const float widen = 1.0f + 2.0f * Gamma(3);
    // A waiting group: x the node's childBase, y its remaining hit bits | interiorMask << 8.
    struct Group {
        uint32_t childBase, bits;
    };
    Group stack[kBvhStackSize];
    uint32_t stackSize = 0;
    uint32_t current = 0;
    bool found = false;
    for (;;) {
        const WideNodeWords n = LoadWideNode(nodes + current);
        const uint32_t meta = n.w[kWideMetaWord];
        const uint32_t interiorMask = meta >> 24;
        const uint32_t leafMask = n.w[kWideLeafMaskWord] & 0xffu;
        const uint32_t occupied = interiorMask | leafMask;
        // Per axis, the plane distance is q * a + b: a = 2^e / d exactly (a power of two scales
        // without rounding), b = (origin - o) / d. The byte q comes as the float 2^23 + q (see
        // WideBiasedByte), so the distance is one fused multiply-add (2^23 + q) * a + c with
        // c = b - 2^23 a per node. The roundings in b and c are absolute errors (of up to
        // gamma(2) |b| and about 2^-24 |c|) that cancellation leaves uncovered by the relative
        // widening below; so near planes use c minus a bound on them and far planes c plus it:
        // the decoded box only grows. NaN (0 * inf, inf - inf) drops a plane, as in SlabTest.
        float a[3], cNear[3], cFar[3];
        uint32_t nearWords[3][2], farWords[3][2];
        for (int axis = 0; axis < 3; ++axis) {
            const float o = axis == 0 ? ray.origin.x : axis == 1 ? ray.origin.y : ray.origin.z;
            const float inv = axis == 0 ? ray.invDir.x : axis == 1 ? ray.invDir.y : ray.invDir.z;
            const float scale = WideScale(int(int8_t(uint8_t(meta >> (8 * axis)))));
            a[axis] = scale * inv;
            const float b = (WordAsFloat(n.w[axis]) - o) * inv;
            const float c = b - 8388608.0f * a[axis];
            const float margin = fabsf(b) * Gamma(5) + fabsf(c) * Gamma(3);
            cNear[axis] = c - margin;
            cFar[axis] = c + margin;
            for (int half = 0; half < 2; ++half) {
                const uint32_t lo = n.w[kWideQloWord + 2 * axis + half];
                const uint32_t hi = n.w[kWideQhiWord + 2 * axis + half];
                nearWords[axis][half] = negative[axis] ? hi : lo;
                farWords[axis][half] = negative[axis] ? lo : hi;
            }
        }
        uint32_t interiorHits = 0, leafHits = 0, nearestBit = 0;
        float nearestT = 0.0f;
#if defined(__CUDA_ARCH__)
#pragma unroll
#endif
        for (uint32_t s = 0; s < uint32_t(kWideArity); ++s) {
            if (((occupied >> s) & 1u) == 0) continue;
            float t0 = 0.0f, t1 = tMax;
            for (int axis = 0; axis < 3; ++axis) {
                const float qNear = WideBiasedByte(nearWords[axis][s >> 2], s & 3u);
                const float qFar = WideBiasedByte(farWords[axis][s >> 2], s & 3u);
                // The accumulators start from 0 and tMax, never NaN, so NaN lanes are dropped.
                t0 = MaxOrKeep(fmaf(qNear, a[axis], cNear[axis]), t0);
                t1 = MinOrKeep(fmaf(qFar, a[axis], cFar[axis]), t1);
            }
            if (t0 <= t1 * widen) {
                const uint32_t bit = 1u << (s ^ octant);
                if ((interiorMask >> s) & 1u) {
                    interiorHits |= bit;
                    if (nearestBit == 0 || t0 < nearestT) {
                        nearestT = t0;
                        nearestBit = bit;
                    }
                } else
                    leafHits |= bit;
            }
        }
        const uint32_t leafBase = n.w[kWideLeafBaseWord];
        while (leafHits != 0) {
            const uint32_t slot = LowestBit(leafHits) ^ octant;
            leafHits &= leafHits - 1u;
            const WideBvhLeaf leaf = leaves[leafBase + BitCount(leafMask & ((1u << slot) - 1u))];
            for (uint32_t i = 0; i < leaf.count; ++i) {
                if (test(leaf.first + i, tMax)) {
                    if constexpr (kQuery == Query::kOccluded) return true;
                    found = true;
                }
            }
        }
        const uint32_t childBase = n.w[kWideChildBaseWord];
        if (interiorHits != 0) {
            // The nearest interior child next; the others wait in the octant order.
            const uint32_t slot = LowestBit(nearestBit) ^ octant;
            const uint32_t rest = interiorHits & ~nearestBit;
            if (rest != 0) stack[stackSize++] = {childBase, rest | (interiorMask << 8)};
            current = WideChildIndex(childBase, interiorMask, slot);
            continue;
        }
        if (stackSize == 0) return found;
        Group& top = stack[stackSize - 1];
        const uint32_t bits = top.bits & 0xffu;
        const uint32_t slot = LowestBit(bits) ^ octant;
        current = WideChildIndex(top.childBase, top.bits >> 8, slot);
        const uint32_t rest = bits & (bits - 1u);
        if (rest != 0)
            top.bits = (top.bits & 0xff00u) | rest;
        else
            --stackSize;
    }
}

}  // namespace rtrt
