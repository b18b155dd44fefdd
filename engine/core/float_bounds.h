#pragma once
// Floating-point error bounds, so that secondary rays leave surfaces without a magic epsilon.
// After pbrt-v4 (Pharr, Jakob, Humphreys), section 6.8 "Managing Rounding Error".
#include <cstring>

#include "engine/core/math.h"

namespace rtrt {

inline constexpr float kMachineEpsilon = 5.96046448e-08f;  // 2^-24, half an ulp of 1

RT_HD inline constexpr float Gamma(int n) {
    return (n * kMachineEpsilon) / (1 - n * kMachineEpsilon);
}

// The same for double arithmetic (unit roundoff 2^-53).
RT_HD inline constexpr double GammaDouble(int n) {
    constexpr double kDoubleEpsilon = 1.1102230246251565e-16;
    return (n * kDoubleEpsilon) / (1 - n * kDoubleEpsilon);
}

RT_HD inline uint32_t FloatToBits(float f) {
#if defined(__CUDA_ARCH__)
    return __float_as_uint(f);
#else
    uint32_t u;
    std::memcpy(&u, &f, sizeof(f));
    return u;
#endif
}
RT_HD inline float BitsToFloat(uint32_t u) {
#if defined(__CUDA_ARCH__)
    return __uint_as_float(u);
#else
    float f;
    std::memcpy(&f, &u, sizeof(u));
    return f;
#endif
}

RT_HD inline bool SignBit(float v) { return (FloatToBits(v) >> 31) != 0; }

RT_HD inline float NextFloatUp(float v) {
    if (v == kInfinity) return v;
    if (v == -0.f) v = 0.f;
    uint32_t ui = FloatToBits(v);
    ui = (v >= 0) ? ui + 1 : ui - 1;
    return BitsToFloat(ui);
}
RT_HD inline float NextFloatDown(float v) {
    if (v == -kInfinity) return v;
    if (v == 0.f) v = -0.f;
    uint32_t ui = FloatToBits(v);
    ui = (v > 0) ? ui - 1 : ui + 1;
    return BitsToFloat(ui);
}

// Moves p, known to within +-pError, along the geometric normal n to the side w points to, far
// enough that a ray from it cannot hit the surface it starts on; then rounds outward.
RT_HD inline vec3 OffsetRayOrigin(vec3 p, vec3 pError, vec3 n, vec3 w) {
    float d = glm::dot(Abs(n), pError);
    vec3 offset = d * n;
    if (glm::dot(w, n) < 0) offset = -offset;
    vec3 po = p + offset;
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0)
            po[i] = NextFloatUp(po[i]);
        else if (offset[i] < 0)
            po[i] = NextFloatDown(po[i]);
    }
    return po;
}

}  // namespace rtrt
