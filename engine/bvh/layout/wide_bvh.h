#pragma once
// A compressed 8-wide BVH for the GPU, collapsed from the binary BVH after Ylitie, Karras and
// Laine (2017), "Efficient Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs": a node
// holds its up to eight children's boxes as 8-bit plane positions against a common origin and a
// power-of-two scale per axis, in 80 bytes (five 16-byte loads).
//
// Boxes only grow under quantisation: each plane is origin + 2^exponent * q, one rounding (the
// product is exact), chosen at build time so that it lies on or outside the child's box. So the
// slab test on the decoded box never misses what the binary tree's test hits.
//
// Children sit in slots by direction from the node's centre (slot s points to -x/+x by bit 0,
// -y/+y by bit 1, -z/+z by bit 2), so that a ray visits them roughly near to far by taking the
// slots in the order s ^ octant, where octant has a bit set per negative direction component.
//
// Leaves are not nodes: a leaf child is a record (first slot, count) of the binary BVH's leaf
// order, so the primitives keep their layout and every other user of the BLAS is unaffected.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "engine/bvh/layout/bvh_node.h"

namespace rtrt {

inline constexpr int kWideArity = 8;

struct alignas(16) WideBvhNode {
    vec3 origin;
    int8_t exponent[3];    // scale of axis a: 2^exponent[a]
    uint8_t interiorMask;  // bit s: slot s holds an interior node
    uint32_t childBase;    // the node's interior children, consecutive in slot order
    uint32_t leafBase;     // its leaf children's records, consecutive in slot order
    uint8_t leafMask;      // bit s: slot s holds a leaf; slots in neither mask are empty
    uint8_t pad[7];
    uint8_t qlo[3][kWideArity];  // [axis][slot]
    uint8_t qhi[3][kWideArity];
};
static_assert(sizeof(WideBvhNode) == 80, "WideBvhNode is five 16-byte words");

struct WideBvhLeaf {
    uint32_t first;  // slot of the binary BVH's leaf order
    uint32_t count;
};

struct WideBvh {
    AlignedVector<WideBvhNode> nodes;  // the root at 0
    std::vector<WideBvhLeaf> leaves;

    size_t Bytes() const {
        return nodes.size() * sizeof(WideBvhNode) + leaves.size() * sizeof(WideBvhLeaf);
    }
};

// The plane a quantised position stands for; the same float on host and device (fma of an exact
// product).
RT_HD inline float WidePlane(float origin, float scale, uint32_t q) {
    return fmaf(scale, float(q), origin);
}

// 2^e as a float for the exponents a WideBvhNode holds (normal range only).
RT_HD inline float WideScale(int e) {
#if defined(__CUDA_ARCH__)
    return __int_as_float(int(uint32_t(e + 127) << 23));
#else
    const uint32_t bits = uint32_t(e + 127) << 23;
    float f;
    std::memcpy(&f, &bits, sizeof(f));
    return f;
#endif
}

// Collapses a binary BVH (root at 0, children at leftFirst and leftFirst + 1) by opening the
// largest-area interior child until a node has eight children or only leaves below it. Returns an
// empty WideBvh (no nodes) when a box is not finite: such a tree stays binary.
WideBvh CollapseToWideBvh(std::span<const BvhNode> binary);

}  // namespace rtrt
