#include "engine/bvh/tlas/dynamic_tlas.h"

#include "engine/bvh/build/bvh_builder.h"
#include "engine/bvh/tlas/tlas.h"

namespace rtrt {

TlasUpdateStats DynamicTlas::Update(std::span<const Instance> instances,
                                    std::span<const Aabb> blasBounds, bool topologyChanged,
                                    std::span<const BlasOutline> blasOutlines) {
    const std::vector<Aabb> bounds = InstanceWorldBounds(instances, blasBounds, blasOutlines);
    TlasUpdateStats stats;
    const bool rebuild = policy_.alwaysRebuild || topologyChanged || !built_ ||
                         tree_.primOrder.size() != instances.size() ||
                         policy_.RebuildsChanged(instances.size());
    if (!rebuild) {
        RefitLbvh(tree_, bounds);
        stats.sahCost = SahCost(tree_.nodes);
        if (stats.sahCost <= (1.0f + policy_.maxSahGrowth) * rebuiltSahCost_) {
            stats.rebuiltSahCost = rebuiltSahCost_;
            return stats;
        }
    }
    tree_ = BuildLbvh(bounds, LbvhLeaves::kPrimitiveIds);
    built_ = true;
    rebuiltSahCost_ = SahCost(tree_.nodes);
    stats.rebuilt = true;
    stats.sahCost = stats.rebuiltSahCost = rebuiltSahCost_;
    return stats;
}

}  // namespace rtrt
