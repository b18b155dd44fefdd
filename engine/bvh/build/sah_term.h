#pragma once
// One node's term of a tree's SAH cost (ComputeStats sums the same terms): relative to the
// root's area, traversal cost for an interior node, intersection cost per primitive for a leaf.
// Position 1 of the pair layout is unused and adds nothing, nor does an empty tree. Summed over
// every position, on either back end, so that rebuild policies see the same cost.
#include "engine/bvh/build/bvh_builder.h"

namespace rtrt {

RT_HD inline float SahNodeTerm(const BvhNode* nodes, uint32_t position) {
    const float rootArea = nodes[0].Bounds().Area();
    if (position == 1 || !(rootArea > 0.0f)) return 0.0f;
    const BvhNode node = nodes[position];
    const float rel = node.Bounds().Area() / rootArea;
    return node.IsLeaf() ? kSahIntersectionCost * float(node.primCount) * rel
                         : kSahTraversalCost * rel;
}

}  // namespace rtrt
