#include "engine/bvh/tlas.h"

#include "engine/bvh/lbvh.h"
#include "engine/core/parallel_for.h"

namespace rtrt {

Aabb TransformBounds(const Affine& m, const Aabb& b) {
    Aabb out;
    if (b.IsEmpty()) return out;
    for (int corner = 0; corner < 8; ++corner) {
        vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
               (corner & 4) ? b.max.z : b.min.z);
        out.Grow(m.Point(p));
    }
    return out;
}

std::vector<Aabb> InstanceWorldBounds(std::span<const Instance> instances,
                                      std::span<const Aabb> blasBounds) {
    std::vector<Aabb> worldBounds(instances.size());
    ParallelFor(0, instances.size(), 4096, [&](size_t i) {
        worldBounds[i] =
            TransformBounds(instances[i].objectToWorld, blasBounds[instances[i].blasId]);
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
