#include "engine/bvh/tlas.h"

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

Tlas BuildTlas(std::span<const Instance> instances, std::span<const Aabb> blasBounds) {
    std::vector<Aabb> worldBounds(instances.size());
    for (size_t i = 0; i < instances.size(); ++i)
        worldBounds[i] =
            TransformBounds(instances[i].objectToWorld, blasBounds[instances[i].blasId]);
    BvhBuildOptions options;
    options.maxLeafSize = 1;  // one instance per leaf: each costs a full BLAS descent
    Bvh bvh = BuildBvh(worldBounds, options);
    return {std::move(bvh.nodes), std::move(bvh.primOrder)};
}

}  // namespace rtrt
