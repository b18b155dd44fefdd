#include "engine/physics_anim/contact_cache.h"

#include <algorithm>
#include <bit>

namespace rtrt::physics {

size_t ContactCache::Hash(uint64_t key) {
    // The finaliser of splitmix64 (Steele, Lea and Flood 2014): every bit of the two indices
    // reaches every bit of the slot.
    key ^= key >> 30;
    key *= 0xbf58476d1ce4e5b9ull;
    key ^= key >> 27;
    key *= 0x94d049bb133111ebull;
    key ^= key >> 31;
    return static_cast<size_t>(key);
}

void ContactCache::Index() {
    // At most half full, so that a probe ends within a few slots.
    const size_t slots = std::bit_ceil(std::max<size_t>(16, 2 * entries_.size()));
    table_.assign(slots, Run{kEmpty, 0, 0});
    mask_ = slots - 1;
    for (size_t begin = 0; begin < entries_.size();) {
        const CachedContact& first = entries_[begin];
        size_t end = begin + 1;
        while (end < entries_.size() && entries_[end].a == first.a && entries_[end].b == first.b) {
            ++end;
        }
        const uint64_t key = Key(first.a, first.b);
        for (size_t slot = Hash(key) & mask_;; slot = (slot + 1) & mask_) {
            Run& run = table_[slot];
            if (run.key == kEmpty) {
                run = {key, static_cast<uint32_t>(begin), static_cast<uint32_t>(end)};
                break;
            }
            const CachedContact& held = entries_[run.begin];
            if (run.key == key && held.a == first.a && held.b == first.b) break;  // keep the first
        }
        begin = end;
    }
}

std::span<const CachedContact> ContactCache::Find(ecs::Entity a, ecs::Entity b) const {
    if (table_.empty()) return {};
    const uint64_t key = Key(a, b);
    for (size_t slot = Hash(key) & mask_;; slot = (slot + 1) & mask_) {
        const Run& run = table_[slot];
        if (run.key == kEmpty) return {};
        if (run.key != key) continue;
        const CachedContact& held = entries_[run.begin];
        // The same indices with other generations: entities that were destroyed and reused.
        if (held.a == a && held.b == b) {
            return {entries_.data() + run.begin, entries_.data() + run.end};
        }
    }
}

}  // namespace rtrt::physics
