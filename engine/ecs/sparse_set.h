#pragma once
// Sparse set of entities: a dense list for iteration plus a paged sparse index for O(1) lookup.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "engine/core/parallel_compact.h"
#include "engine/ecs/entity.h"

namespace rtrt::ecs {

// Maps entity handles to positions in a packed list. The sparse index (entity index -> dense
// position) is split into pages allocated on first use, so a set holding a few entities with
// large indices costs a few pages rather than one slot per index ever issued.
class SparseSet {
  public:
    static constexpr uint32_t kAbsent = std::numeric_limits<uint32_t>::max();

    // Dense position of e, or kAbsent. The dense list keeps full handles, so a stale handle whose
    // index now belongs to another entity misses instead of finding that entity.
    uint32_t Find(Entity e) const {
        const uint32_t page = e.index >> kPageBits;
        if (page >= pages_.size() || !pages_[page]) return kAbsent;
        const uint32_t pos = pages_[page][e.index & kPageMask];
        return pos != kAbsent && dense_[pos] == e ? pos : kAbsent;
    }
    bool Contains(Entity e) const { return Find(e) != kAbsent; }

    // Appends e and returns its position. No entity with e's index may be in the set.
    uint32_t Insert(Entity e) {
        const auto pos = static_cast<uint32_t>(dense_.size());
        dense_.push_back(e);
        SparseSlot(e.index) = pos;
        return pos;
    }

    // Moves the last entity into pos and drops the last place (swap-and-pop). Owners of arrays
    // kept parallel to the dense list do the same move.
    void SwapAndPop(uint32_t pos) {
        const Entity removed = dense_[pos];
        const Entity last = dense_.back();
        dense_[pos] = last;
        SparseSlot(last.index) = pos;
        SparseSlot(removed.index) = kAbsent;  // after the line above: removed may be last
        dense_.pop_back();
    }

    // Appends entities[i] for every i where keep(i) holds, in order: the positions that Insert
    // one after another would give, found in parallel (ParallelCompact, which calls keep twice
    // per entity). None that keep accepts may be in the set already, no two entities may share
    // an index (the caller's contract: a breach leaves the set inconsistent), and the set must
    // have a page for each (CoverPagesOf): the parallel writes then touch only their own slots.
    template <typename Keep>
    void AppendWhere(std::span<const Entity> entities, std::vector<uint32_t>& chunkStarts,
                     const Keep& keep) {
        const size_t base = dense_.size();
        dense_.resize(base + entities.size());
        const uint32_t added =
            ParallelCompact(entities.size(), chunkStarts, keep, [&](size_t i, uint32_t at) {
                const Entity e = entities[i];
                const auto pos = static_cast<uint32_t>(base + at);
                dense_[pos] = e;
                pages_[e.index >> kPageBits][e.index & kPageMask] = pos;
            });
        dense_.resize(base + added);
    }
    // Gives this set a sparse page wherever other has one, so that other's entities can be
    // added without allocating.
    void CoverPagesOf(const SparseSet& other) {
        for (uint32_t page = 0; page < other.pages_.size(); ++page) {
            if (other.pages_[page]) Page(page);
        }
    }

    void Clear() {
        for (const Entity e : dense_) SparseSlot(e.index) = kAbsent;
        dense_.clear();
    }

    size_t Size() const { return dense_.size(); }
    bool Empty() const { return dense_.empty(); }
    std::span<const Entity> Entities() const { return dense_; }

  private:
    static constexpr uint32_t kPageBits = 12;  // 4096 entries, 16 KiB per page
    static constexpr uint32_t kPageSize = 1u << kPageBits;
    static constexpr uint32_t kPageMask = kPageSize - 1;

    uint32_t& SparseSlot(uint32_t index) { return Page(index >> kPageBits)[index & kPageMask]; }
    uint32_t* Page(uint32_t page) {
        if (page >= pages_.size()) pages_.resize(page + 1);
        if (!pages_[page]) {
            pages_[page] = std::make_unique_for_overwrite<uint32_t[]>(kPageSize);
            std::fill_n(pages_[page].get(), kPageSize, kAbsent);
        }
        return pages_[page].get();
    }

    std::vector<std::unique_ptr<uint32_t[]>> pages_;
    std::vector<Entity> dense_;
};

}  // namespace rtrt::ecs
