#pragma once
// std::vector whose storage starts on a 64-byte cache line, so that a 32-byte BVH node pair at an
// even index never straddles two lines.
#include <cstddef>
#include <new>
#include <vector>

namespace rtrt {

template <typename T>
struct CacheLineAllocator {
    // The names std::allocator_traits looks for.
    using value_type = T;  // NOLINT(readability-identifier-naming)
    static constexpr std::align_val_t kAlignment{64};

    CacheLineAllocator() = default;
    template <typename U>
    CacheLineAllocator(const CacheLineAllocator<U>&) {}

    // NOLINTNEXTLINE(readability-identifier-naming)
    T* allocate(size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlignment)); }
    // NOLINTNEXTLINE(readability-identifier-naming)
    void deallocate(T* p, size_t) { ::operator delete(p, kAlignment); }
    template <typename U>
    bool operator==(const CacheLineAllocator<U>&) const {
        return true;
    }
};

template <typename T>
using AlignedVector = std::vector<T, CacheLineAllocator<T>>;

}  // namespace rtrt
