#include "engine/bvh/tlas/tlas.h"

#include "engine/bvh/build/lbvh.h"
#include "engine/core/parallel_for.h"

namespace rtrt {

std::vector<Aabb> InstanceWorldBounds(std::span<const Instance> instances,
                                      std::span<const Aabb> blasBounds,
                                      std::span<const BlasOutline> blasOutlines) {
    std::vector<Aabb> worldBounds(instances.size());
    const InstanceWorldBoxes boxes{instances.data(), blasBounds.data(),
                                   blasOutlines.empty() ? nullptr : blasOutlines.data()};
    ParallelFor(0, instances.size(), 4096, [&](size_t i) { worldBounds[i] = boxes[i]; });
    return worldBounds;
}

std::vector<uint32_t> TlasLeafInstances(const Tlas& tlas) {
    std::vector<uint32_t> ids;
    for (const BvhNode& node : tlas.nodes)
        if (node.IsLeaf()) ids.push_back(node.leftFirst);
    return ids;
}

Tlas BuildTlas(std::span<const Instance> instances, std::span<const Aabb> blasBounds,
               TlasBuilder builder, std::span<const BlasOutline> blasOutlines) {
    const std::vector<Aabb> worldBounds = InstanceWorldBounds(instances, blasBounds, blasOutlines);
    if (builder == TlasBuilder::kLbvh)
        return {std::move(BuildLbvh(worldBounds, LbvhLeaves::kPrimitiveIds).nodes)};
    BvhBuildOptions options;
    options.maxLeafSize = 1;  // one instance per leaf: each costs a full BLAS descent
    Bvh bvh = BuildBvh(worldBounds, options);
    for (BvhNode& node : bvh.nodes) {
        if (!node.IsLeaf()) continue;
        // Only a tree cut off at the builder's depth limit (a pathological placement) has a
        // leaf of several instances, which a TLAS cannot name: the LBVH's depth is bounded by
        // its keys instead.
        if (node.primCount > 1)
            return BuildTlas(instances, blasBounds, TlasBuilder::kLbvh, blasOutlines);
        node.leftFirst = bvh.primOrder[node.leftFirst];
    }
    return {std::move(bvh.nodes)};
}

}  // namespace rtrt
