#pragma once
// Last step's touching contacts, for warm starting: each pair of bodies' contacts together, found
// by the pair in constant time.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/core/math.h"
#include "engine/ecs/entity.h"

namespace rtrt::physics {

// Keyed by entity, so that the contacts survive the per-frame gathering of bodies.
struct CachedContact {
    ecs::Entity a;
    ecs::Entity b;
    vec3 localPoint;  // in a's frame
    float normalImpulse;
    float tangentImpulse1;
    float tangentImpulse2;
};

class ContactCache {
  public:
    // Filled by the caller, each pair's contacts in one run; Index() must follow.
    std::vector<CachedContact>& Entries() { return entries_; }
    // Builds the table of runs (an open-addressing hash table, linear probing), in parallel. A
    // pair that appears in two runs is found with its first.
    void Index();
    // The contacts of (a, b) in that order, or none.
    std::span<const CachedContact> Find(ecs::Entity a, ecs::Entity b) const;
    // Starts loading the table slot where Find(a, b) begins: a caller that knows its next keys
    // overlaps their cache misses.
    void Prefetch(ecs::Entity a, ecs::Entity b) const;

  private:
    struct Run {
        uint64_t key;   // kEmpty: a free slot
        uint64_t span;  // begin << 32 | end in entries_ (kEmpty while being inserted)
    };
    static constexpr uint64_t kEmpty = ~uint64_t{0};
    static uint64_t Key(ecs::Entity a, ecs::Entity b) {
        return (uint64_t{a.index} << 32) | b.index;
    }
    static size_t Hash(uint64_t key);

    std::vector<CachedContact> entries_;
    std::vector<Run> table_;
    size_t mask_ = 0;
};

}  // namespace rtrt::physics
