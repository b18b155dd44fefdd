#pragma once
// From runtime accuracy bits to the compile-time variant: one instantiation per combination.
#include <type_traits>

#include "bench/accuracy/accuracy_policy.h"

namespace rtrt {

template <uint32_t kCandidate = 0, typename Fn>
decltype(auto) DispatchAccuracy(uint32_t accuracy, Fn&& fn) {
    if constexpr (kCandidate == kAllAccuracyBits) {
        return fn(std::integral_constant<uint32_t, kCandidate>{});
    } else {
        if ((accuracy & kAllAccuracyBits) == kCandidate)
            return fn(std::integral_constant<uint32_t, kCandidate>{});
        return DispatchAccuracy<kCandidate + 1>(accuracy, std::forward<Fn>(fn));
    }
}

}  // namespace rtrt
