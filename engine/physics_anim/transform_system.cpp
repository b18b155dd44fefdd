#include "engine/physics_anim/transform_system.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <tuple>

#include "engine/core/parallel_for.h"

namespace rtrt::physics {

using ecs::Entity;
using ecs::Registry;

namespace {

bool EntityLess(Entity a, Entity b) {
    return std::tie(a.index, a.generation) < std::tie(b.index, b.generation);
}
bool PairLess(const std::pair<Entity, Entity>& a, const std::pair<Entity, Entity>& b) {
    if (a.first != b.first) return EntityLess(a.first, b.first);
    return EntityLess(a.second, b.second);
}

}  // namespace

bool SetParent(Registry& registry, Entity child, Entity parent) {
    if (!registry.Valid(child) || !registry.Valid(parent) || child == parent) return false;
    // Walk up from the new parent: meeting child means child would become its own ancestor. The
    // hop limit also stops on a cycle already present above parent.
    const size_t maxHops = registry.Count<Parent>() + 1;
    Entity ancestor = parent;
    for (size_t hops = 0; hops <= maxHops; ++hops) {
        if (ancestor == child) return false;
        const Parent* link = registry.Get<Parent>(ancestor);
        if (link == nullptr || !registry.Valid(link->entity))
            return registry.Add(child, Parent{parent});
        ancestor = link->entity;
    }
    return false;
}

bool ClearParent(Registry& registry, Entity child) { return registry.Remove<Parent>(child); }

void TransformSystem::Update(Registry& registry) {
    stats_.lastRecomputed = 0;
    stats_.lastCyclic = 0;
    const bool linksChanged =
        registry.ChangedCount<Parent>() > 0 || registry.Count<Parent>() != childOf_.size();
    if (!linksChanged && registry.ChangedCount<LocalTransform>() == 0) return;

    if (!linksChanged && SameSeedsAsLastPass(registry)) {
        // The same entities moved under the same links: the set and its order are last pass's.
        ++stats_.repeated;
    } else {
        CollectDirty(registry, linksChanged);
    }
    stats_.lastCyclic = cyclic_;
    ComputeAndWrite(registry);
    registry.ClearChanged<LocalTransform>();
    registry.ClearChanged<Parent>();
}

bool TransformSystem::SameSeedsAsLastPass(const Registry& registry) const {
    if (registry.ChangedCount<LocalTransform>() != seedCount_ || seedCount_ == 0) return false;
    bool same = true;
    registry.EachChanged<LocalTransform>([&](Entity e, const LocalTransform&) {
        const uint32_t i = e.index < slot_.size() ? slot_[e.index] : UINT32_MAX;
        same = same && i < dirty_.size() && dirty_[i].entity == e && seeded_[i];
    });
    return same;
}

void TransformSystem::CollectDirty(Registry& registry, bool linksChanged) {
    if (++stamp_ == 0) {  // the stamps wrapped: forget every old one
        std::fill(visited_.begin(), visited_.end(), 0u);
        stamp_ = 1;
    }
    pending_.clear();
    set_.clear();
    if (linksChanged) RebuildLinks(registry);
    localSeeds_.clear();
    registry.EachChanged<LocalTransform>([&](Entity e, LocalTransform&) {
        localSeeds_.push_back(e);
        Seed(e);
    });
    registry.EachChanged<Parent>([&](Entity e, Parent&) { Seed(e); });
    CollectDescendants();

    // Parents before children: sorted by depth, then entity index (alive entities have distinct
    // indices), as packed keys, which sort much faster than the entries themselves.
    order_.clear();
    uint32_t cyclic = 0;
    for (const Entity e : set_) {
        bool loops = false;
        const uint32_t depth = Depth(registry, e, loops);
        cyclic += loops;
        order_.push_back(uint64_t(loops ? 0 : depth) << 32 | e.index);
        if (e.index >= slot_.size()) slot_.resize(e.index + 1);
        slot_[e.index] = loops ? UINT32_MAX : 0;  // a loop member is a root: no parent entry
    }
    tbb::parallel_sort(order_.begin(), order_.end());
    dirty_.clear();
    dirty_.reserve(order_.size());
    {
        // set_ holds each entity once; find it again from its index.
        if (setAt_.size() < slot_.size()) setAt_.resize(slot_.size());
        for (uint32_t k = 0; k < set_.size(); ++k) setAt_[set_[k].index] = k;
        for (uint64_t key : order_) {
            const Entity e = set_[setAt_[uint32_t(key)]];
            const uint32_t depth = uint32_t(key >> 32);
            const bool root = depth == 0 || slot_[e.index] == UINT32_MAX;
            const Parent* link = root ? nullptr : registry.Get<Parent>(e);
            dirty_.push_back({depth, e, link ? link->entity : ecs::kNullEntity});
        }
    }
    for (uint32_t i = 0; i < dirty_.size(); ++i) slot_[dirty_[i].entity.index] = i;
    cyclic_ = cyclic;
    // Which entries moved by their own pose: the next pass may find the same seeds.
    seeded_.assign(dirty_.size(), 0);
    for (const Entity e : localSeeds_) seeded_[slot_[e.index]] = 1;
    seedCount_ = localSeeds_.size();
}

void TransformSystem::ComputeAndWrite(Registry& registry) {
    // Each depth's matrices in parallel (they read only shallower results and the registry),
    // written where the entity has its WorldTransform already (distinct components, and no
    // parent outside the set is written); then the marks and new components in order, on this
    // thread.
    worlds_.resize(dirty_.size());
    written_.resize(dirty_.size());
    Registry& writer = registry;
    const Registry& reader = registry;
    for (size_t begin = 0; begin < dirty_.size();) {
        size_t end = begin;
        while (end < dirty_.size() && dirty_[end].depth == dirty_[begin].depth) ++end;
        ParallelFor(begin, end, 256, [&](size_t i) {
            const Dirty& d = dirty_[i];
            glm::mat4 parentWorld(1.0f);
            if (!d.parent.IsNull()) {
                if (const glm::mat4* computed = ComputedWorld(d.parent)) {
                    parentWorld = *computed;
                } else if (const WorldTransform* stored = reader.Get<WorldTransform>(d.parent)) {
                    parentWorld = stored->objectToWorld;
                }
            }
            const LocalTransform* local = reader.Get<LocalTransform>(d.entity);
            worlds_[i] = local != nullptr ? parentWorld * ToMatrix(*local) : parentWorld;
            WorldTransform* world = writer.Get<WorldTransform>(d.entity);
            if (world != nullptr) world->objectToWorld = worlds_[i];
            written_[i] = world != nullptr;
        });
        begin = end;
    }
    for (size_t i = 0; i < dirty_.size(); ++i) {
        const Dirty& d = dirty_[i];
        if (written_[i]) {
            registry.MarkChanged<WorldTransform>(d.entity);
        } else {
            registry.Add(d.entity, WorldTransform{worlds_[i]});  // adding marks it changed
        }
    }
    stats_.lastRecomputed = static_cast<uint32_t>(dirty_.size());
    stats_.recomputed += dirty_.size();
}

void TransformSystem::RebuildLinks(const Registry& registry) {
    std::vector<std::pair<Entity, Entity>> next;
    next.reserve(registry.Count<Parent>());
    registry.View<const Parent>().Each(
        [&](Entity child, const Parent& link) { next.emplace_back(child, link.entity); });
    std::sort(next.begin(), next.end(), PairLess);

    // A child that gained, lost or changed its parent moves even if its own pose did not.
    size_t i = 0;
    size_t j = 0;
    while (i < childOf_.size() || j < next.size()) {
        if (j == next.size() ||
            (i < childOf_.size() && EntityLess(childOf_[i].first, next[j].first))) {
            if (registry.Valid(childOf_[i].first)) Seed(childOf_[i].first);  // lost its parent
            ++i;
        } else if (i == childOf_.size() || EntityLess(next[j].first, childOf_[i].first)) {
            Seed(next[j].first);  // gained one
            ++j;
        } else {
            if (childOf_[i].second != next[j].second) Seed(next[j].first);
            ++i;
            ++j;
        }
    }
    childOf_ = std::move(next);
    children_.clear();
    for (const auto& [child, parent] : childOf_) children_.emplace_back(parent, child);
    std::sort(children_.begin(), children_.end(), PairLess);
    // Each parent index's run of children_, found in one step rather than a search.
    uint32_t maxIndex = 0;
    for (const auto& [parent, child] : children_) maxIndex = std::max(maxIndex, parent.index);
    childStart_.assign(children_.empty() ? 1 : maxIndex + 2, 0);
    for (const auto& [parent, child] : children_) ++childStart_[parent.index + 1];
    for (size_t i = 1; i < childStart_.size(); ++i) childStart_[i] += childStart_[i - 1];
    depth_.clear();  // depths follow the links
}

void TransformSystem::Seed(Entity e) {
    if (e.index >= visited_.size()) visited_.resize(e.index + 1, 0u);
    if (visited_[e.index] == stamp_) return;
    visited_[e.index] = stamp_;
    pending_.push_back(e);
}

void TransformSystem::CollectDescendants() {
    while (!pending_.empty()) {
        const Entity e = pending_.back();
        pending_.pop_back();
        set_.push_back(e);
        if (e.index + 1 >= childStart_.size()) continue;
        for (uint32_t k = childStart_[e.index]; k < childStart_[e.index + 1]; ++k)
            if (children_[k].first == e) Seed(children_[k].second);
    }
}

uint32_t TransformSystem::Depth(const Registry& registry, Entity e, bool& cyclic) {
    if (e.index < depth_.size() && depth_[e.index] != 0) return depth_[e.index] - 1;
    // Walk up to a root or an entity whose depth is known, then number the way back down.
    const size_t maxHops = registry.Count<Parent>();
    chain_.clear();
    uint32_t base = 0;
    for (Entity at = e;;) {
        if (at.index < depth_.size() && depth_[at.index] != 0) {
            base = depth_[at.index] - 1;
            break;
        }
        chain_.push_back(at);
        const Parent* link = registry.Get<Parent>(at);
        if (link == nullptr || !registry.Valid(link->entity)) {
            base = 0;
            // `at` is a root: depth 0; the rest of the chain counts up from it.
            if (at.index >= depth_.size()) depth_.resize(at.index + 1, 0);
            depth_[at.index] = 1;
            chain_.pop_back();
            break;
        }
        if (chain_.size() > maxHops) {
            cyclic = true;
            return 0;
        }
        at = link->entity;
    }
    for (size_t k = chain_.size(); k-- > 0;) {
        ++base;
        const Entity c = chain_[k];
        if (c.index >= depth_.size()) depth_.resize(c.index + 1, 0);
        depth_[c.index] = base + 1;
    }
    return depth_[e.index] - 1;
}

const glm::mat4* TransformSystem::ComputedWorld(Entity e) const {
    if (e.index >= visited_.size() || visited_[e.index] != stamp_) return nullptr;
    const uint32_t i = slot_[e.index];
    if (i >= dirty_.size() || dirty_[i].entity != e) return nullptr;
    return &worlds_[i];
}

void AddTransformSystem(ecs::Scheduler& scheduler, TransformSystem& system) {
    scheduler.AddSystem("animation", "transforms",
                        [&system](Registry& registry, float) { system.Update(registry); });
}

}  // namespace rtrt::physics
