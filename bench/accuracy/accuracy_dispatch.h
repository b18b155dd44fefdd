#pragma once
// From runtime accuracy bits to the compile-time variant: one instantiation per combination.
#include <type_traits>

#include "bench/accuracy/accuracy_policy.h"

namespace rtrt {

// Only the combinations in kUsedAccuracyVariants are instantiated; any other falls back to the
// default (IsUsedAccuracy lets callers refuse it first).
template <size_t kIndex = 0, typename Fn>
decltype(auto) DispatchAccuracy(uint32_t accuracy, Fn&& fn) {
    constexpr size_t kCount = sizeof(kUsedAccuracyVariants) / sizeof(kUsedAccuracyVariants[0]);
    if constexpr (kIndex == kCount) {
        return fn(std::integral_constant<uint32_t, kAccuracyDefault>{});
    } else {
        constexpr uint32_t kCandidate = kUsedAccuracyVariants[kIndex];
        if ((accuracy & kAllAccuracyBits) == kCandidate)
            return fn(std::integral_constant<uint32_t, kCandidate>{});
        return DispatchAccuracy<kIndex + 1>(accuracy, std::forward<Fn>(fn));
    }
}

inline bool IsUsedAccuracy(uint32_t accuracy) {
    for (uint32_t v : kUsedAccuracyVariants)
        if (v == (accuracy & kAllAccuracyBits)) return true;
    return false;
}

}  // namespace rtrt
