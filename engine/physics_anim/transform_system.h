#pragma once
// Keeps WorldTransform up to date from LocalTransform and Parent, touching only what changed.
#include <cstdint>
#include <utility>
#include <vector>

#include "engine/ecs/registry.h"
#include "engine/ecs/scheduler.h"
#include "engine/physics_anim/transform.h"

namespace rtrt::physics {

// Makes parent the parent of child. False, and no change, when either handle is not alive, when
// child == parent, or when child is already an ancestor of parent (the link would close a cycle).
// Inside a deferred phase the link appears at the phase's end; two links recorded in one phase
// can still close a cycle, which TransformSystem then detects and breaks (see its Stats).
bool SetParent(ecs::Registry& registry, ecs::Entity child, ecs::Entity parent);
// Makes child a root again. False if it had no parent.
bool ClearParent(ecs::Registry& registry, ecs::Entity child);

struct TransformStats {
    uint64_t recomputed = 0;      // world transforms written since construction
    uint32_t lastRecomputed = 0;  // in the last Update
    uint32_t lastCyclic = 0;      // entities found in or under a parent cycle in the last Update
    uint64_t repeated = 0;        // Updates that reused the last pass's set and order
};

// Recomputes WorldTransform = parent's WorldTransform * ToMatrix(LocalTransform) for the entities
// whose LocalTransform was marked changed, whose Parent changed, and all their descendants;
// parents are computed before children (sorted by depth). Everything else is left alone, so a
// static entity costs nothing after its first pass. Entities in the set without a WorldTransform
// get one; each written WorldTransform is marked changed (the consumer, extraction, clears those
// marks). Update consumes the LocalTransform and Parent marks: it clears them when done.
//
// An entity whose ancestor chain loops is treated as a root (and counted in lastCyclic). A child
// whose parent was destroyed keeps its world transform until its own pose changes, then it is
// treated as a root. A dirty entity without a LocalTransform uses the identity.
//
// An animated scene moves the same entities every frame: when the links did not change and the
// marked LocalTransforms are exactly the last pass's, the last pass's set and order are reused
// (no search for descendants, no sort).
class TransformSystem {
  public:
    void Update(ecs::Registry& registry);
    const TransformStats& Stats() const { return stats_; }

  private:
    struct Dirty {
        uint32_t depth;
        ecs::Entity entity;
        ecs::Entity parent;  // null for roots and broken links
    };

    // Whether the marked LocalTransforms are exactly the ones that seeded the last pass.
    bool SameSeedsAsLastPass(const ecs::Registry& registry) const;
    // The entities to recompute (the seeds and their descendants) into dirty_, parents first.
    void CollectDirty(ecs::Registry& registry, bool linksChanged);
    // Each dirty entity's world matrix, written and marked changed.
    void ComputeAndWrite(ecs::Registry& registry);
    // Rebuilds the child lists from the Parent pool and seeds every child whose link changed.
    void RebuildLinks(const ecs::Registry& registry);
    void Seed(ecs::Entity e);
    void CollectDescendants();
    // Hops from e up to its root, remembered until the links change; cyclic is set when the
    // chain loops.
    uint32_t Depth(const ecs::Registry& registry, ecs::Entity e, bool& cyclic);
    // The world matrix computed in this pass for e (a parent of a later entry), or null.
    const glm::mat4* ComputedWorld(ecs::Entity e) const;

    std::vector<std::pair<ecs::Entity, ecs::Entity>> childOf_;   // (child, parent), by child
    std::vector<std::pair<ecs::Entity, ecs::Entity>> children_;  // (parent, child), by parent
    std::vector<uint32_t> childStart_;  // per parent index: its first entry in children_
    std::vector<uint32_t> visited_;     // per entity index: stamp_ when in this pass's set
    std::vector<uint32_t> slot_;        // per entity index: its entry in dirty_ (this pass)
    std::vector<uint32_t> setAt_;       // per entity index: its position in set_ (this pass)
    std::vector<uint32_t> depth_;       // per entity index: depth + 1, 0 = not known yet
    std::vector<ecs::Entity> chain_;    // Depth's walk
    uint32_t stamp_ = 0;
    std::vector<ecs::Entity> pending_;
    std::vector<ecs::Entity> set_;
    std::vector<uint64_t> order_;  // (depth << 32 | entity index) of the set, sorted
    std::vector<Dirty> dirty_;
    std::vector<uint8_t> seeded_;  // parallel to dirty_: seeded by its own LocalTransform
    std::vector<ecs::Entity> localSeeds_;
    size_t seedCount_ = 0;           // entries of seeded_ set
    uint32_t cyclic_ = 0;            // entries of dirty_ in or under a parent cycle
    std::vector<glm::mat4> worlds_;  // parallel to dirty_
    std::vector<uint8_t> written_;   // parallel to dirty_: its WorldTransform written in place
    TransformStats stats_;
};

// Adds system.Update to phase "animation" under the name "transforms"; add it after the systems
// that write LocalTransform in that phase (animation), so extraction sees this frame's poses.
void AddTransformSystem(ecs::Scheduler& scheduler, TransformSystem& system);

}  // namespace rtrt::physics
