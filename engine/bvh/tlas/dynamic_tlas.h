#pragma once
// The per-frame TLAS of the runtime on the CPU: an LBVH over instance world bounds (its leaves
// hold instance indices, as every TLAS's: tlas.h), rebuilt when instances
// were added or removed (or on request) and otherwise refit, until refitting has let the SAH cost
// drift more than a threshold above the cost of the last rebuild.
#include <span>

#include "engine/bvh/build/lbvh.h"
#include "engine/bvh/tlas/instance.h"

namespace rtrt {

// The default is the runtime's: refit while the tree stays good, rebuild when it has drifted.
struct TlasPolicy {
    bool alwaysRebuild = false;  // a fresh LBVH every frame (benchmarks of the build)
    float maxSahGrowth = 0.25f;  // with refits: rebuild once cost > (1 + this) x rebuilt cost

    static constexpr TlasPolicy AlwaysRebuild() { return {true, 0.25f}; }
};

struct TlasUpdateStats {
    bool rebuilt = false;
    float sahCost = 0.0f;         // after this update
    float rebuiltSahCost = 0.0f;  // at the last rebuild
};

class DynamicTlas {
  public:
    explicit DynamicTlas(TlasPolicy policy = {}) : policy_(policy) {}

    // Brings the tree up to date with the instances' current transforms. topologyChanged: an
    // instance was added or removed since the last update (refitting cannot follow that).
    // blasSpheres: BlasSphere of each BLAS (tlas.h), or empty.
    TlasUpdateStats Update(std::span<const Instance> instances, std::span<const Aabb> blasBounds,
                           bool topologyChanged, std::span<const vec4> blasSpheres = {});

    const Lbvh& Tree() const { return tree_; }
    const TlasPolicy& Policy() const { return policy_; }

  private:
    TlasPolicy policy_;
    Lbvh tree_;
    float rebuiltSahCost_ = 0.0f;
    bool built_ = false;
};

}  // namespace rtrt
