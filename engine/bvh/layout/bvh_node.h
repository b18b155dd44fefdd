#pragma once
#include "engine/core/aligned_vector.h"
#include "engine/geometry/aabb.h"

namespace rtrt {

// Flattened binary BVH node, 32 bytes. An interior node's children sit side by side at
// leftFirst and leftFirst + 1 (the pair fills one 64-byte line; index 1 is left unused so pairs
// start at even indices). A leaf (primCount > 0) covers primitives [leftFirst, leftFirst +
// primCount) of the BLAS's reordered primitive array.
struct alignas(32) BvhNode {
    vec3 boundsMin;
    uint32_t leftFirst;
    vec3 boundsMax;
    uint32_t primCount;

    RT_HD bool IsLeaf() const { return primCount > 0; }
    RT_HD Aabb Bounds() const { return {boundsMin, boundsMax}; }
    RT_HD void SetBounds(const Aabb& b) {
        boundsMin = b.min;
        boundsMax = b.max;
    }
};
static_assert(sizeof(BvhNode) == 32, "BvhNode is 32 bytes: two children per cache line");

inline constexpr uint32_t kBvhStackSize = 64;

}  // namespace rtrt
