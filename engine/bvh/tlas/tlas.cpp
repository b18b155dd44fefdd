#include "engine/bvh/tlas/tlas.h"

#include "engine/bvh/build/lbvh.h"
#include "engine/core/parallel_for.h"

namespace rtrt {

std::vector<Aabb> InstanceWorldBounds(std::span<const Instance> instances,
                                      std::span<const Aabb> blasBounds) {
    std::vector<Aabb> worldBounds(instances.size());
    ParallelFor(0, instances.size(), 4096, [&](size_t i) {
        worldBounds[i] =
            TransformBounds(instances[i].ObjectToWorld(), blasBounds[instances[i].blasId]);
    });
    return worldBounds;
}

Tlas BuildTlas(std::span<const Instance> instances, std::span<const Aabb> blasBounds,
               TlasBuilder builder) {
    const std::vector<Aabb> worldBounds = InstanceWorldBounds(instances, blasBounds);
    if (builder == TlasBuilder::kLbvh) {
        Lbvh lbvh = BuildLbvh(worldBounds);
        return {std::move(lbvh.nodes), std::move(lbvh.primOrder)};
    }
    BvhBuildOptions options;
    options.maxLeafSize = 1;  // one instance per leaf: each costs a full BLAS descent
    Bvh bvh = BuildBvh(worldBounds, options);
    return {std::move(bvh.nodes), std::move(bvh.primOrder)};
}

}  // namespace rtrt
