#pragma once
// A 4-wide BVH for the CPU back end, collapsed from the binary BVH: each node holds its four
// children's boxes as structure-of-arrays so one SSE instruction tests all four. Leaves are not
// nodes: a child with count > 0 is a leaf covering slots [child, child + count) of the same
// leaf-ordered primitives as the binary BVH. The GPU keeps the binary layout.
#include <span>

#include "engine/bvh/layout/bvh_node.h"

namespace rtrt {

struct alignas(64) Bvh4Node {
    float minX[4], minY[4], minZ[4];
    float maxX[4], maxY[4], maxZ[4];
    uint32_t child[4];  // interior child: node index; leaf child: first primitive slot
    uint32_t count[4];  // 0 for an interior child (or an empty slot, whose box is empty)
};
static_assert(sizeof(Bvh4Node) == 128, "Bvh4Node is two cache lines");

// Byte offsets of the six plane arrays inside a node, for picking near/far planes per ray.
inline constexpr uint32_t kBvh4MinOffset = 0, kBvh4MaxOffset = 48;

// Collapses a binary BVH (root at 0, children at leftFirst and leftFirst + 1) by pulling up the
// largest-area grandchildren until each node has four children or only leaves below it.
AlignedVector<Bvh4Node> CollapseToBvh4(std::span<const BvhNode> binary);

}  // namespace rtrt
