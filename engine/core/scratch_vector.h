#pragma once
// std::vector whose resize leaves new elements of a trivially constructible type uninitialised, for
// scratch arrays that are sized to an upper bound and then filled (ParallelCompact's outputs):
// value-initialising the bound's elements would be a serial pass that writes zeros each time.
#include <new>
#include <utility>
#include <vector>

namespace rtrt {

template <typename T>
struct DefaultInitAllocator : std::allocator<T> {
    DefaultInitAllocator() = default;
    template <typename U>
    DefaultInitAllocator(const DefaultInitAllocator<U>&) {}

    // The names std::allocator_traits looks for: with no arguments, default-initialise.
    template <typename U>
    void construct(U* p) noexcept {  // NOLINT(readability-identifier-naming)
        ::new (static_cast<void*>(p)) U;
    }
    template <typename U, typename... Args>
    void construct(U* p, Args&&... args) {  // NOLINT(readability-identifier-naming)
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

template <typename T>
using ScratchVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace rtrt
