#include "engine/bvh/tlas/tlas.h"

#include "engine/bvh/build/lbvh.h"
#include "engine/core/parallel_for.h"

namespace rtrt {

vec4 BlasSphere(const Blas& blas) {
    if (blas.kind != GeometryKind::kSpheres || blas.spheres.size() != 1) return vec4(0.0f);
    const Sphere& s = blas.spheres[0];
    return vec4(s.center, s.radius);
}

std::vector<vec4> BlasSpheres(std::span<const std::shared_ptr<const Blas>> blases) {
    std::vector<vec4> spheres;
    spheres.reserve(blases.size());
    for (const auto& blas : blases) spheres.push_back(BlasSphere(*blas));
    return spheres;
}

std::vector<Aabb> InstanceWorldBounds(std::span<const Instance> instances,
                                      std::span<const Aabb> blasBounds,
                                      std::span<const vec4> blasSpheres) {
    std::vector<Aabb> worldBounds(instances.size());
    const InstanceWorldBoxes boxes{instances.data(), blasBounds.data(),
                                   blasSpheres.empty() ? nullptr : blasSpheres.data()};
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
               TlasBuilder builder, std::span<const vec4> blasSpheres) {
    const std::vector<Aabb> worldBounds = InstanceWorldBounds(instances, blasBounds, blasSpheres);
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
            return BuildTlas(instances, blasBounds, TlasBuilder::kLbvh, blasSpheres);
        node.leftFirst = bvh.primOrder[node.leftFirst];
    }
    return {std::move(bvh.nodes)};
}

}  // namespace rtrt
