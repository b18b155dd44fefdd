#pragma once
// Iteration over the entities that have every one of several components.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <tuple>
#include <type_traits>
#include <utility>

#include "engine/ecs/component_pool.h"
#include "engine/ecs/entity.h"
#include "engine/ecs/sparse_set.h"

namespace rtrt::ecs {

// Walks the smallest of the pools and probes the others, so the cost follows the rarest
// component. A const component type gives const access. A null pool (a type never added to the
// registry) makes the view empty. The view points into the registry's pools and lives no longer.
template <typename... Ts>
class View {
    static_assert(sizeof...(Ts) > 0, "a view names at least one component type");

  public:
    template <typename T>
    using PoolPtr =
        std::conditional_t<std::is_const_v<T>, const ComponentPool<std::remove_const_t<T>>*,
                           ComponentPool<T>*>;

    explicit View(PoolPtr<Ts>... pools) : pools_(pools...) {}

    // Calls fn(Entity, Ts&...) once per entity that has all Ts, in the smallest pool's order.
    // Structural changes made meanwhile must be deferred (phases, ScopedDeferral): an immediate
    // add or remove on a viewed pool moves components under the loop.
    template <typename Fn>
    void Each(Fn&& fn) const {
        EachImpl(fn, std::index_sequence_for<Ts...>{});
    }

  private:
    static constexpr size_t kCount = sizeof...(Ts);

    template <typename Fn, size_t... kI>
    void EachImpl(Fn& fn, std::index_sequence<kI...>) const {
        const PoolBase* driver = Smallest();
        if (driver == nullptr) return;
        const std::span<const Entity> entities = driver->Entities();
        for (uint32_t i = 0; i < entities.size(); ++i) {
            const Entity e = entities[i];
            const std::array<uint32_t, kCount> pos{PositionIn<kI>(driver, e, i)...};
            if (((pos[kI] == SparseSet::kAbsent) || ...)) continue;
            fn(e, std::get<kI>(pools_)->At(pos[kI])...);
        }
    }

    // The driver's position is the loop index; other pools are probed through their sparse index.
    template <size_t kI>
    uint32_t PositionIn(const PoolBase* driver, Entity e, uint32_t i) const {
        const PoolBase* pool = std::get<kI>(pools_);
        return pool == driver ? i : pool->Find(e);
    }

    // The smallest pool, or null when any pool is missing.
    const PoolBase* Smallest() const {
        const std::array<const PoolBase*, kCount> pools = std::apply(
            [](auto*... p) { return std::array<const PoolBase*, kCount>{p...}; }, pools_);
        const PoolBase* best = pools[0];
        for (const PoolBase* pool : pools) {
            if (pool == nullptr) return nullptr;
            if (pool->Size() < best->Size()) best = pool;
        }
        return best;
    }

    std::tuple<PoolPtr<Ts>...> pools_;
};

}  // namespace rtrt::ecs
