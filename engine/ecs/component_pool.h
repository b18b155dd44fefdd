#pragma once
// Component storage: the owners in a sparse set and their components packed in the same order.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/ecs/entity.h"
#include "engine/ecs/sparse_set.h"

namespace rtrt::ecs {

namespace detail {
inline uint32_t NextComponentTypeId() {
    static std::atomic<uint32_t> next{0};
    return next.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace detail

// A small dense id per component type, shared by all registries; indexes the pool tables.
template <typename T>
uint32_t ComponentTypeId() {
    static const uint32_t kId = detail::NextComponentTypeId();
    return kId;
}

// What every pool offers without knowing its component type: the owner set, the changed set, and
// removal, which destroying an entity needs for each pool. Views and Get use the typed pool, so
// the one virtual call is never made per component on the hot path.
class PoolBase {
  public:
    PoolBase() = default;
    PoolBase(const PoolBase&) = delete;
    PoolBase& operator=(const PoolBase&) = delete;
    virtual ~PoolBase() = default;

    // Removes e's component by swap-and-pop; false if e has none (or the handle is stale).
    virtual bool Remove(Entity e) = 0;

    uint32_t Find(Entity e) const { return owners_.Find(e); }
    bool Contains(Entity e) const { return owners_.Contains(e); }
    size_t Size() const { return owners_.Size(); }
    std::span<const Entity> Entities() const { return owners_.Entities(); }

    // Change tracking: owners marked since the last ClearChanged, each once, in marking order
    // (disturbed by swap-and-pop when a marked owner loses the component). Adding or replacing a
    // component marks it; removing it unmarks it, so every listed entity still has one.
    void MarkChanged(Entity e) {
        if (owners_.Contains(e) && !changed_.Contains(e)) changed_.Insert(e);
    }
    // Marks entities as MarkChanged would one after another, the checks in parallel. No two may
    // share an index (the same entity twice, or two generations of one).
    void MarkChanged(std::span<const Entity> entities) {
        changed_.CoverPagesOf(owners_);
        changed_.AppendWhere(entities, markChunks_, [&](size_t i) {
            return owners_.Contains(entities[i]) && !changed_.Contains(entities[i]);
        });
    }
    bool IsChanged(Entity e) const { return changed_.Contains(e); }
    std::span<const Entity> ChangedEntities() const { return changed_.Entities(); }
    void ClearChanged() {
        changed_.Clear();
        ++clears_;
    }
    // How many times ClearChanged ran: a walk of the changed list ends where this moves.
    uint64_t Clears() const { return clears_; }

  protected:
    // Appends e (which must be absent) to the owners, marks it changed, returns its position.
    uint32_t InsertOwner(Entity e) {
        const uint32_t pos = owners_.Insert(e);
        changed_.Insert(e);
        return pos;
    }
    // Swap-and-pop of the owner at pos; the derived pool moves its components to match.
    void EraseOwnerAt(uint32_t pos) {
        const uint32_t changedPos = changed_.Find(owners_.Entities()[pos]);
        if (changedPos != SparseSet::kAbsent) changed_.SwapAndPop(changedPos);
        owners_.SwapAndPop(pos);
    }

  private:
    SparseSet owners_;
    SparseSet changed_;
    uint64_t clears_ = 0;
    std::vector<uint32_t> markChunks_;  // the bulk MarkChanged's scratch
};

// Components of one type, packed in the owners' dense order so views walk contiguous memory.
// Adding or removing a component of this type invalidates pointers into the pool.
template <typename T>
class ComponentPool final : public PoolBase {
    static_assert(std::is_same_v<T, std::remove_cvref_t<T>>, "pools hold plain component types");
    static_assert(std::is_move_constructible_v<T> && std::is_move_assignable_v<T>,
                  "swap-and-pop moves components");

  public:
    // Adds e's component, or replaces it if e already has one; marks it changed either way.
    T& Add(Entity e, T component) {
        const uint32_t pos = Find(e);
        if (pos != SparseSet::kAbsent) {
            components_[pos] = std::move(component);
            MarkChanged(e);
            return components_[pos];
        }
        components_.push_back(std::move(component));
        InsertOwner(e);
        return components_.back();
    }

    bool Remove(Entity e) override {
        const uint32_t pos = Find(e);
        if (pos == SparseSet::kAbsent) return false;
        EraseOwnerAt(pos);
        if (pos + 1 != components_.size()) components_[pos] = std::move(components_.back());
        components_.pop_back();
        return true;
    }

    T* TryGet(Entity e) {
        const uint32_t pos = Find(e);
        return pos == SparseSet::kAbsent ? nullptr : &components_[pos];
    }
    const T* TryGet(Entity e) const {
        const uint32_t pos = Find(e);
        return pos == SparseSet::kAbsent ? nullptr : &components_[pos];
    }

    // By dense position (parallel to Entities()), for views.
    T& At(uint32_t pos) { return components_[pos]; }
    const T& At(uint32_t pos) const { return components_[pos]; }

  private:
    std::vector<T> components_;
};

}  // namespace rtrt::ecs
