#pragma once
// std::vector whose resize leaves new elements uninitialised, for scratch arrays of trivial
// elements that are sized to an upper bound and then filled (ParallelCompact's outputs):
// value-initialising the bound's elements would be a serial pass that writes zeros each time.
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace rtrt {

template <typename T>
struct DefaultInitAllocator : std::allocator<T> {
    static_assert(std::is_trivially_default_constructible_v<T>,
                  "only elements that need no initialisation may be left without it");
    // The names std::allocator_traits looks for.
    template <typename U>
    struct rebind {  // NOLINT(readability-identifier-naming)
        using other = DefaultInitAllocator<U>;
    };

    DefaultInitAllocator() = default;
    template <typename U>
    DefaultInitAllocator(const DefaultInitAllocator<U>&) {}

    // With no arguments, default-initialise: for a trivial type, nothing is written.
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
