#pragma once
// The per-frame TLAS of the runtime on the CPU: an LBVH over instance world bounds (its leaves
// hold instance indices, as every TLAS's: tlas.h), rebuilt when instances were added or removed
// (or on request) and, under the runtime's policy, on every update (the frame renderers update
// only when records changed). A policy may instead refit the tree, until refitting has let its
// SAH cost drift more than a threshold above the cost of the last rebuild.
#include <cstddef>
#include <cstdint>
#include <span>

#include "engine/bvh/build/lbvh.h"
#include "engine/bvh/tlas/blas_outline.h"
#include "engine/bvh/tlas/instance.h"

namespace rtrt {

// The default is the runtime's: the tree is built afresh whenever instances moved. A policy with
// a smaller rebuildChangedUpTo refits larger scenes while their trees stay good and rebuilds them
// once they have drifted.
struct TlasPolicy {
    bool alwaysRebuild = false;  // a fresh LBVH every frame (benchmarks of the build)
    float maxSahGrowth = 0.25f;  // with refits: rebuild once cost > (1 + this) x rebuilt cost
    // Up to this many instances an update that changed any rebuilds instead of refitting; by
    // default at any size. Scenes whose refit trees degrade traced faster on a fresh tree, long
    // before the refit tree's SAH cost had grown by maxSahGrowth and by more than the rebuild
    // costs over a refit: demo_physics (465 instances) on both back ends
    // (bench/results/tlas-policy-h100-2026-12-05.txt) and bench_physics_10k (10,005) on both
    // (tlas-policy-large-h100-2026-12-05.txt, tlas-policy-large-cpu-vm-2026-12-05.txt); the
    // other demos were level.
    uint32_t rebuildChangedUpTo = UINT32_MAX;

    static constexpr TlasPolicy AlwaysRebuild() { return {true, 0.25f}; }
    // Refits at any size (what the tests of refitting need).
    static constexpr TlasPolicy RefitWhileGood() { return {false, 0.25f, 0}; }

    bool RebuildsChanged(size_t instances) const { return instances <= rebuildChangedUpTo; }
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
    // blasOutlines: each BLAS's outline (blas_outline.h), or empty: the boxes alone.
    TlasUpdateStats Update(std::span<const Instance> instances, std::span<const Aabb> blasBounds,
                           bool topologyChanged, std::span<const BlasOutline> blasOutlines = {});

    const Lbvh& Tree() const { return tree_; }
    const TlasPolicy& Policy() const { return policy_; }

  private:
    TlasPolicy policy_;
    Lbvh tree_;
    float rebuiltSahCost_ = 0.0f;
    bool built_ = false;
};

}  // namespace rtrt
