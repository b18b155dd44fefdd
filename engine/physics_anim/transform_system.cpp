#include "engine/physics_anim/transform_system.h"

#include <algorithm>
#include <tuple>

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

    if (++stamp_ == 0) {  // the stamps wrapped: forget every old one
        std::fill(visited_.begin(), visited_.end(), 0u);
        stamp_ = 1;
    }
    pending_.clear();
    set_.clear();
    if (linksChanged) RebuildLinks(registry);
    registry.EachChanged<LocalTransform>([&](Entity e, LocalTransform&) { Seed(e); });
    registry.EachChanged<Parent>([&](Entity e, Parent&) { Seed(e); });
    CollectDescendants();

    dirty_.clear();
    for (const Entity e : set_) {
        bool cyclic = false;
        const uint32_t depth = Depth(registry, e, cyclic);
        if (cyclic) {
            ++stats_.lastCyclic;
            dirty_.push_back({0, e, ecs::kNullEntity});
            continue;
        }
        dirty_.push_back(
            {depth, e, depth > 0 ? registry.Get<Parent>(e)->entity : ecs::kNullEntity});
    }
    std::sort(dirty_.begin(), dirty_.end(), [](const Dirty& a, const Dirty& b) {
        return a.depth != b.depth ? a.depth < b.depth : EntityLess(a.entity, b.entity);
    });

    worlds_.resize(dirty_.size());
    for (size_t i = 0; i < dirty_.size(); ++i) {
        const Dirty& d = dirty_[i];
        glm::mat4 parentWorld(1.0f);
        if (!d.parent.IsNull()) {
            if (const glm::mat4* computed = ComputedWorld(d.depth - 1, d.parent)) {
                parentWorld = *computed;
            } else if (const WorldTransform* stored = registry.Get<WorldTransform>(d.parent)) {
                parentWorld = stored->objectToWorld;
            }
        }
        const LocalTransform* local = registry.Get<LocalTransform>(d.entity);
        worlds_[i] = local != nullptr ? parentWorld * ToMatrix(*local) : parentWorld;
        if (WorldTransform* world = registry.Get<WorldTransform>(d.entity)) {
            world->objectToWorld = worlds_[i];
            registry.MarkChanged<WorldTransform>(d.entity);
        } else {
            registry.Add(d.entity, WorldTransform{worlds_[i]});  // adding marks it changed
        }
    }
    stats_.lastRecomputed = static_cast<uint32_t>(dirty_.size());
    stats_.recomputed += dirty_.size();
    registry.ClearChanged<LocalTransform>();
    registry.ClearChanged<Parent>();
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
        auto it = std::lower_bound(
            children_.begin(), children_.end(), std::pair{e, Entity{0, 0}},
            [](const auto& a, const auto& b) { return EntityLess(a.first, b.first); });
        for (; it != children_.end() && it->first == e; ++it) Seed(it->second);
    }
}

uint32_t TransformSystem::Depth(const Registry& registry, Entity e, bool& cyclic) const {
    const size_t maxHops = registry.Count<Parent>();
    uint32_t depth = 0;
    for (const Parent* link = registry.Get<Parent>(e);
         link != nullptr && registry.Valid(link->entity);
         link = registry.Get<Parent>(link->entity)) {
        if (++depth > maxHops) {
            cyclic = true;
            return 0;
        }
    }
    return depth;
}

const glm::mat4* TransformSystem::ComputedWorld(uint32_t depth, Entity e) const {
    const auto it = std::lower_bound(
        dirty_.begin(), dirty_.end(), std::pair{depth, e},
        [](const Dirty& d, const std::pair<uint32_t, Entity>& key) {
            return d.depth != key.first ? d.depth < key.first : EntityLess(d.entity, key.second);
        });
    if (it == dirty_.end() || it->depth != depth || it->entity != e) return nullptr;
    return &worlds_[static_cast<size_t>(it - dirty_.begin())];
}

void AddTransformSystem(ecs::Scheduler& scheduler, TransformSystem& system) {
    scheduler.AddSystem("animation", "transforms",
                        [&system](Registry& registry, float) { system.Update(registry); });
}

}  // namespace rtrt::physics
