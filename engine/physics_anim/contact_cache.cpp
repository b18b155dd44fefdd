#include "engine/physics_anim/contact_cache.h"

#include <immintrin.h>

#include <algorithm>
#include <atomic>
#include <bit>

#include "engine/core/parallel_for.h"

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
    table_.resize(slots);
    ParallelFor(0, slots, 8192, [&](size_t slot) { table_[slot] = Run{kEmpty, kEmpty}; });
    mask_ = slots - 1;
    // In parallel, each run inserted by the thread that meets its first entry. A slot is claimed
    // for a key (the two indices) by a compare-and-swap; its run follows as one 64-bit store, so
    // a thread that finds the key waits for the run before it compares entities (the same indices
    // may name other generations: another pair, which probes on). A pair in two runs keeps its
    // first, by an atomic minimum. Slots may differ from run to run; what Find returns does not.
    ParallelFor(0, entries_.size(), 2048, [&](size_t begin) {
        const CachedContact& first = entries_[begin];
        if (begin > 0 && entries_[begin - 1].a == first.a && entries_[begin - 1].b == first.b) {
            return;  // inside a run
        }
        size_t end = begin + 1;
        while (end < entries_.size() && entries_[end].a == first.a && entries_[end].b == first.b) {
            ++end;
        }
        const uint64_t key = Key(first.a, first.b);
        const uint64_t span = (uint64_t{begin} << 32) | end;
        for (size_t slot = Hash(key) & mask_;; slot = (slot + 1) & mask_) {
            std::atomic_ref<uint64_t> slotKey(table_[slot].key);
            std::atomic_ref<uint64_t> slotSpan(table_[slot].span);
            uint64_t held = kEmpty;
            if (slotKey.compare_exchange_strong(held, key, std::memory_order_acq_rel)) {
                uint64_t current = kEmpty;
                while (span < current && !slotSpan.compare_exchange_weak(current, span)) {
                }
                return;
            }
            if (held != key) continue;
            uint64_t current = slotSpan.load(std::memory_order_acquire);
            while (current == kEmpty) current = slotSpan.load(std::memory_order_acquire);
            const CachedContact& owner = entries_[current >> 32];
            if (owner.a != first.a || owner.b != first.b) continue;
            while (span < current && !slotSpan.compare_exchange_weak(current, span)) {
            }
            return;
        }
    });
}

void ContactCache::Prefetch(ecs::Entity a, ecs::Entity b) const {
    if (table_.empty()) return;
    _mm_prefetch(reinterpret_cast<const char*>(&table_[Hash(Key(a, b)) & mask_]), _MM_HINT_T0);
}

std::span<const CachedContact> ContactCache::Find(ecs::Entity a, ecs::Entity b) const {
    if (table_.empty()) return {};
    const uint64_t key = Key(a, b);
    for (size_t slot = Hash(key) & mask_;; slot = (slot + 1) & mask_) {
        const Run& run = table_[slot];
        if (run.key == kEmpty) return {};
        if (run.key != key) continue;
        const auto begin = static_cast<uint32_t>(run.span >> 32);
        const auto end = static_cast<uint32_t>(run.span);
        const CachedContact& held = entries_[begin];
        // The same indices with other generations: entities that were destroyed and reused.
        if (held.a == a && held.b == b) return {entries_.data() + begin, entries_.data() + end};
    }
}

}  // namespace rtrt::physics
