#include "engine/bvh/tlas/blas_outline.h"

#include <algorithm>

#include "engine/bvh/tlas/tlas.h"

namespace rtrt {

BlasOutline OutlineOfBlas(const Blas& blas, bool deforms) {
    BlasOutline outline;
    outline.sphere = BlasSphere(blas);
    if (deforms || blas.nodes.empty() || blas.nodes[0].IsLeaf()) return outline;
    std::vector<uint32_t> parts{0};
    while (parts.size() < BlasOutline::kMaxParts) {
        // The interior node of largest surface area, split into its two children.
        auto widest = parts.end();
        for (auto it = parts.begin(); it != parts.end(); ++it) {
            const BvhNode& node = blas.nodes[*it];
            if (!node.IsLeaf() && (widest == parts.end() ||
                                   node.Bounds().Area() > blas.nodes[*widest].Bounds().Area()))
                widest = it;
        }
        if (widest == parts.end()) break;
        const uint32_t left = blas.nodes[*widest].leftFirst;
        *widest = left;
        parts.push_back(left + 1);
    }
    for (uint32_t index : parts) {
        const Aabb box = blas.nodes[index].Bounds();
        if (box.IsEmpty()) continue;  // holds nothing
        const vec3 centre = 0.5f * (box.min + box.max);
        vec3 half;
        for (int i = 0; i < 3; ++i)
            half[i] = NextFloatUp(std::max(box.max[i] - centre[i], centre[i] - box.min[i]));
        outline.partCentre[outline.partCount] = centre;
        outline.partHalf[outline.partCount] = half;
        ++outline.partCount;
    }
    return outline;
}

std::vector<BlasOutline> BlasOutlines(std::span<const std::shared_ptr<const Blas>> blases) {
    std::vector<BlasOutline> outlines;
    outlines.reserve(blases.size());
    for (const auto& blas : blases) outlines.push_back(OutlineOfBlas(*blas));
    return outlines;
}

}  // namespace rtrt
