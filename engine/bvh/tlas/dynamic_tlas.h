#pragma once
// The per-frame TLAS of the runtime on the CPU: an LBVH over instance world bounds (its leaves
// hold instance indices, as every TLAS's: tlas.h), rebuilt when instances were added or removed
// (or on request) and, in a scene of few instances, on every update (the frame renderers update
// only when records changed); a larger scene's tree is otherwise refit, until refitting has let
// the SAH cost drift more than a threshold above the cost of the last rebuild.
#include <cstddef>
#include <cstdint>
#include <span>

#include "engine/bvh/build/lbvh.h"
#include "engine/bvh/tlas/instance.h"

namespace rtrt {

// The default is the runtime's: a small scene's tree is built afresh whenever instances moved; a
// larger one is refit while the tree stays good and rebuilt when it has drifted.
struct TlasPolicy {
    bool alwaysRebuild = false;  // a fresh LBVH every frame (benchmarks of the build)
    float maxSahGrowth = 0.25f;  // with refits: rebuild once cost > (1 + this) x rebuilt cost
    // Up to this many instances an update that changed any rebuilds instead of refitting: an
    // LBVH of so few builds in about a refit's time, while a refit tree of a moving pile traces
    // measurably slower long before its SAH cost has grown by maxSahGrowth
    // (bench/results/tlas-policy-h100-2026-12-05.txt).
    uint32_t rebuildChangedUpTo = 4096;

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
