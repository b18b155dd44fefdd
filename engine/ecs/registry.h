#pragma once
// The registry: entities, their component pools, views, change tracking and deferral.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/ecs/command_buffer.h"
#include "engine/ecs/component_pool.h"
#include "engine/ecs/entity.h"
#include "engine/ecs/view.h"

namespace rtrt::ecs {

// Owns entities and one pool per component type. Components are plain structs.
//
// Every call taking an Entity detects a stale handle (its entity was destroyed, even if the index
// now belongs to another entity): Valid and Has say false, Get returns null, Destroy, Add and
// Remove return false and change nothing.
//
// Deferral: between BeginDeferred and the matching EndDeferred (each scheduler phase is one such
// span) Create, Destroy, Add and Remove are recorded and applied in order at EndDeferred, so views
// can be iterated while they are requested. Until then the world reads as before: a created
// entity is not yet Valid (its handle may already be given components and destroyed), a destroyed
// one still is. Outside deferral the changes are immediate.
class Registry {
  public:
    Registry() = default;
    // A moved-from registry is empty, as a new one.
    Registry(Registry&& other) noexcept { *this = std::move(other); }
    Registry& operator=(Registry&& other) noexcept {
        if (this == &other) return *this;
        entities_ = std::exchange(other.entities_, EntityAllocator());
        pools_ = std::exchange(other.pools_, {});
        commands_ = std::exchange(other.commands_, CommandBuffer());
        deferDepth_ = std::exchange(other.deferDepth_, 0);
        return *this;
    }

    Entity Create();
    bool Destroy(Entity e);
    bool Valid(Entity e) const { return entities_.IsAlive(e); }
    size_t AliveCount() const { return entities_.AliveCount(); }

    // Adds e's component or replaces the one it has (Add<T>(e) adds a value-initialised T).
    template <typename T>
    bool Add(Entity e, T component = T{});
    // True when a component was removed, or when deferred, when the removal was recorded.
    template <typename T>
    bool Remove(Entity e);

    template <typename T>
    bool Has(Entity e) const {
        const ComponentPool<T>* pool = FindPool<T>();
        return pool != nullptr && pool->Contains(e);
    }
    // Null when e lacks T or the handle is stale. Adding or removing a T invalidates the pointer.
    template <typename T>
    T* Get(Entity e) {
        ComponentPool<T>* pool = FindPool<T>();
        return pool == nullptr ? nullptr : pool->TryGet(e);
    }
    template <typename T>
    const T* Get(Entity e) const {
        const ComponentPool<T>* pool = FindPool<T>();
        return pool == nullptr ? nullptr : pool->TryGet(e);
    }
    template <typename T>
    size_t Count() const {
        const ComponentPool<T>* pool = FindPool<T>();
        return pool == nullptr ? 0 : pool->Size();
    }

    // View<A, const B>() gives mutable A and const B; a const registry gives views of const types.
    template <typename... Ts>
    ecs::View<Ts...> View() {
        return ecs::View<Ts...>(FindPool<std::remove_const_t<Ts>>()...);
    }
    template <typename... Ts>
    ecs::View<Ts...> View() const {
        static_assert((std::is_const_v<Ts> && ...), "a const registry gives views of const types");
        return ecs::View<Ts...>(FindPool<std::remove_const_t<Ts>>()...);
    }

    // Change tracking, so that extraction touches only what moved: MarkChanged<T>(e) records that
    // e's T changed (ignored if e has no T); adding or replacing a T marks it too. EachChanged
    // calls fn(Entity, T&) once per entity marked since ClearChanged<T>, in marking order; an
    // entity that lost its T meanwhile is not listed. Marks made during EachChanged are kept
    // for the next pass but not visited by this one; structural changes fn makes are deferred
    // until it has visited them all (an immediate Remove would reorder the list it walks), and a
    // ClearChanged<T> made by fn ends the walk.
    template <typename T>
    void MarkChanged(Entity e) {
        if (ComponentPool<T>* pool = FindPool<T>()) pool->MarkChanged(e);
    }
    // Marks many, as one by one in their order, checked in parallel: for systems that move
    // thousands of entities a frame. No two may share an index.
    template <typename T>
    void MarkChanged(std::span<const Entity> entities) {
        if (ComponentPool<T>* pool = FindPool<T>()) pool->MarkChanged(entities);
    }
    template <typename T, typename Fn>
    void EachChanged(Fn&& fn) {
        ComponentPool<T>* pool = FindPool<T>();
        if (pool == nullptr) return;
        BeginDeferred();
        struct EndsDeferral {
            Registry& registry;
            ~EndsDeferral() { registry.EndDeferred(); }
        } endsDeferral{*this};
        EachChangedIn(*pool, fn);
    }
    template <typename T, typename Fn>
    void EachChanged(Fn&& fn) const {
        if (const ComponentPool<T>* pool = FindPool<T>()) EachChangedIn(*pool, fn);
    }
    // Whether e's T is marked (a system that derives from other entities' components, such as
    // a skin from its joints, asks this of each of them).
    template <typename T>
    bool IsChanged(Entity e) const {
        const ComponentPool<T>* pool = FindPool<T>();
        return pool != nullptr && pool->IsChanged(e);
    }
    template <typename T>
    size_t ChangedCount() const {
        const ComponentPool<T>* pool = FindPool<T>();
        return pool == nullptr ? 0 : pool->ChangedEntities().size();
    }
    template <typename T>
    void ClearChanged() {
        if (ComponentPool<T>* pool = FindPool<T>()) pool->ClearChanged();
    }

    // Spans nest; the outermost EndDeferred applies the recorded changes.
    void BeginDeferred() { ++deferDepth_; }
    void EndDeferred();
    bool Deferring() const { return deferDepth_ > 0; }

  private:
    // Alive, or reserved by a deferred Create: commands on it may be recorded.
    bool Known(Entity e) const { return entities_.IsAlive(e) || entities_.IsReserved(e); }
    bool DestroyNow(Entity e);
    void Flush();

    template <typename T>
    ComponentPool<T>* FindPool() const {
        const uint32_t id = ComponentTypeId<T>();
        return id < pools_.size() ? static_cast<ComponentPool<T>*>(pools_[id].get()) : nullptr;
    }
    template <typename T>
    ComponentPool<T>& AssurePool() {
        const uint32_t id = ComponentTypeId<T>();
        if (id >= pools_.size()) pools_.resize(id + 1);
        if (!pools_[id]) pools_[id] = std::make_unique<ComponentPool<T>>();
        return static_cast<ComponentPool<T>&>(*pools_[id]);
    }
    template <typename Pool, typename Fn>
    static void EachChangedIn(Pool& pool, Fn& fn) {
        const size_t count = pool.ChangedEntities().size();
        const uint64_t clears = pool.Clears();
        for (size_t i = 0;
             i < count && pool.Clears() == clears && i < pool.ChangedEntities().size(); ++i) {
            // Re-read the span: a mark made by fn may grow (and move) the changed list.
            const Entity e = pool.ChangedEntities()[i];
            fn(e, pool.At(pool.Find(e)));
        }
    }

    EntityAllocator entities_;
    std::vector<std::unique_ptr<PoolBase>> pools_;  // by component type id; null if never added
    CommandBuffer commands_;
    int deferDepth_ = 0;
};

// Defers structural changes for its lifetime, e.g. around a loop that destroys what it visits.
class ScopedDeferral {
  public:
    explicit ScopedDeferral(Registry& registry) : registry_(registry) { registry_.BeginDeferred(); }
    ~ScopedDeferral() { registry_.EndDeferred(); }
    ScopedDeferral(const ScopedDeferral&) = delete;
    ScopedDeferral& operator=(const ScopedDeferral&) = delete;

  private:
    Registry& registry_;
};

template <typename T>
bool Registry::Add(Entity e, T component) {
    static_assert(std::is_same_v<T, std::remove_cvref_t<T>>, "components are plain types");
    if (Deferring()) {
        if (!Known(e)) return false;
        AssurePool<T>();  // the flush adds through the type-erased pool
        commands_.Add(e, std::move(component));
        return true;
    }
    if (!Valid(e)) return false;
    AssurePool<T>().Add(e, std::move(component));
    return true;
}

template <typename T>
bool Registry::Remove(Entity e) {
    ComponentPool<T>* pool = FindPool<T>();
    if (pool == nullptr) return false;
    if (Deferring()) {
        if (!Known(e)) return false;
        commands_.Remove<T>(e);
        return true;
    }
    return pool->Remove(e);
}

}  // namespace rtrt::ecs
