#pragma once
// Entity handles (slot index + generation) and the allocator that issues them.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace rtrt::ecs {

// Which slot, and which occupant of that slot: destroying an entity bumps its slot's generation,
// so every older handle to the slot stops matching instead of aliasing the next occupant.
struct Entity {
    static constexpr uint32_t kNullIndex = std::numeric_limits<uint32_t>::max();

    uint32_t index = kNullIndex;
    uint32_t generation = 0;

    constexpr bool IsNull() const { return index == kNullIndex; }
    friend constexpr bool operator==(Entity, Entity) = default;
};
static_assert(sizeof(Entity) == 8);

inline constexpr Entity kNullEntity{};

// Issues entity handles and says which are alive. Freed indices are reused last-in first-out.
//
// Generation policy: a slot's generation grows by one per destroy and never wraps. A slot whose
// generation has reached maxGeneration is retired when destroyed (its index is never handed out
// again), so no handle is ever issued twice. With 32-bit generations that costs one 8-byte slot
// per 2^32 reuses of an index.
class EntityAllocator {
  public:
    static constexpr uint32_t kMaxGeneration = std::numeric_limits<uint32_t>::max();

    // Tests pass a small maxGeneration to reach retirement quickly.
    explicit EntityAllocator(uint32_t maxGeneration = kMaxGeneration)
        : maxGeneration_(maxGeneration) {}

    Entity Create() {
        const Entity e = Reserve();
        Activate(e);
        return e;
    }

    // Takes a slot now but leaves the entity not alive until Activate: deferred creation hands
    // out its handle at once, and the entity appears at the end of the phase.
    Entity Reserve();
    // Makes a reserved entity alive; false (and no change) for any other handle.
    bool Activate(Entity e);
    // False (and no change) for a handle that is not alive: stale, reserved, null or forged.
    bool Destroy(Entity e);

    bool IsAlive(Entity e) const { return Matches(e, SlotState::kAlive); }
    bool IsReserved(Entity e) const { return Matches(e, SlotState::kReserved); }
    size_t AliveCount() const { return aliveCount_; }

  private:
    enum class SlotState : uint8_t { kFree, kReserved, kAlive, kRetired };
    struct Slot {
        uint32_t generation;
        SlotState state;
    };

    bool Matches(Entity e, SlotState state) const {
        return e.index < slots_.size() && slots_[e.index].generation == e.generation &&
               slots_[e.index].state == state;
    }

    std::vector<Slot> slots_;
    std::vector<uint32_t> freeList_;
    size_t aliveCount_ = 0;
    uint32_t maxGeneration_;
};

inline Entity EntityAllocator::Reserve() {
    if (!freeList_.empty()) {
        const uint32_t index = freeList_.back();
        freeList_.pop_back();
        slots_[index].state = SlotState::kReserved;
        return {index, slots_[index].generation};
    }
    // kNullIndex marks the null handle, so it is never issued.
    if (slots_.size() >= Entity::kNullIndex)
        throw std::length_error("ecs: entity indices exhausted");
    slots_.push_back({0, SlotState::kReserved});
    return {static_cast<uint32_t>(slots_.size() - 1), 0};
}

inline bool EntityAllocator::Activate(Entity e) {
    if (!IsReserved(e)) return false;
    slots_[e.index].state = SlotState::kAlive;
    ++aliveCount_;
    return true;
}

inline bool EntityAllocator::Destroy(Entity e) {
    if (!IsAlive(e)) return false;
    --aliveCount_;
    Slot& slot = slots_[e.index];
    if (slot.generation >= maxGeneration_) {
        slot.state = SlotState::kRetired;
        return true;
    }
    ++slot.generation;
    slot.state = SlotState::kFree;
    freeList_.push_back(e.index);
    return true;
}

}  // namespace rtrt::ecs
