#pragma once
// The per-node step of Karras 2012 ("Maximizing Parallelism in the Construction of BVHs, Octrees,
// and k-d Trees"), shared by the CPU and CUDA LBVH builders: internal node i finds the range of
// sorted keys it covers and where that range splits, independently of every other node.
#include <cstdint>

#include "engine/core/rt_hd.h"

#if !defined(__CUDA_ARCH__)
#include <bit>
#endif

namespace rtrt {

RT_HD inline int CountLeadingZeros(uint32_t v) {
#if defined(__CUDA_ARCH__)
    return __clz(v);
#else
    return std::countl_zero(v);
#endif
}

// Length of the common prefix of keys i and j, -1 outside the array; equal keys compare their
// indices instead, so that every pair of keys differs (the paper's section 4). Codes: an array of
// keys, or anything whose operator[] gives key i.
template <class Codes>
RT_HD inline int CommonPrefix(const Codes& codes, uint32_t n, int64_t i, int64_t j) {
    if (j < 0 || j >= int64_t(n)) return -1;
    const uint32_t a = uint32_t(codes[i]), b = uint32_t(codes[j]);
    if (a == b) return 32 + CountLeadingZeros(uint32_t(i) ^ uint32_t(j));
    return CountLeadingZeros(a ^ b);
}

// Internal node i covers sorted keys [first, last]; its children are split and split + 1, each a
// leaf when it is an end of the range.
struct KarrasNode {
    uint32_t first, last, split;
};

template <class Codes>
RT_HD inline KarrasNode KarrasInternalNode(const Codes& codes, uint32_t n, uint32_t index) {
    const int64_t i = index;
    const int d = CommonPrefix(codes, n, i, i + 1) - CommonPrefix(codes, n, i, i - 1) > 0 ? 1 : -1;
    // The range extends in direction d while keys share more than deltaMin prefix bits with i.
    const int deltaMin = CommonPrefix(codes, n, i, i - d);
    int64_t lengthMax = 2;
    while (CommonPrefix(codes, n, i, i + lengthMax * d) > deltaMin) lengthMax *= 2;
    int64_t length = 0;
    for (int64_t t = lengthMax / 2; t >= 1; t /= 2)
        if (CommonPrefix(codes, n, i, i + (length + t) * d) > deltaMin) length += t;
    const int64_t j = i + length * d;
    // The split is where the prefix shared with i shrinks below the node's own prefix.
    const int deltaNode = CommonPrefix(codes, n, i, j);
    int64_t split = 0;
    int64_t t = length;
    do {
        t = (t + 1) / 2;
        if (CommonPrefix(codes, n, i, i + (split + t) * d) > deltaNode) split += t;
    } while (t > 1);
    const int64_t gamma = i + split * d + (d < 0 ? -1 : 0);
    return {uint32_t(i < j ? i : j), uint32_t(i < j ? j : i), uint32_t(gamma)};
}

}  // namespace rtrt
