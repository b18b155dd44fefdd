#pragma once
// GLM vector types everywhere; GLM marks its functions __host__ __device__ by itself under nvcc
// (do not define GLM_FORCE_CUDA, see BUILD_NOTES.md).
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

#include "engine/core/rt_hd.h"

namespace rtrt {

using glm::ivec2;
using glm::vec2;
using glm::vec3;
using glm::vec4;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInfinity = __builtin_huge_valf();

// Min and max that return `acc` when `candidate` is NaN, and compile to one instruction on both
// back ends (std::fmin/fmax are library calls on x86 without -ffast-math). `acc` must not be NaN.
RT_HD inline float MaxOrKeep(float candidate, float acc) {
#if defined(__CUDA_ARCH__)
    return fmaxf(candidate, acc);
#else
    return candidate > acc ? candidate : acc;
#endif
}
RT_HD inline float MinOrKeep(float candidate, float acc) {
#if defined(__CUDA_ARCH__)
    return fminf(candidate, acc);
#else
    return candidate < acc ? candidate : acc;
#endif
}

RT_HD inline float MaxComponent(vec3 v) { return fmaxf(v.x, fmaxf(v.y, v.z)); }
RT_HD inline int MaxDimension(vec3 v) {
    return (v.x > v.y) ? (v.x > v.z ? 0 : 2) : (v.y > v.z ? 1 : 2);
}
RT_HD inline vec3 Abs(vec3 v) { return vec3(fabsf(v.x), fabsf(v.y), fabsf(v.z)); }
RT_HD inline float Luminance(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// V itself where its squared length lies well inside float's normal range, else V divided by its
// largest component's magnitude: glm::normalize and cross products of the result neither
// overflow nor underflow (a direction given as [3e38, 3e38, 3e38] or [0, 1e-40, 0]), while
// ordinary inputs keep their bits. V must be finite.
inline vec3 ScaledForNormalize(vec3 v) {
    const float squared = glm::dot(v, v);
    if (squared >= 1e-30f && squared <= 1e30f) return v;
    const float largest = MaxComponent(Abs(v));
    return largest > 0.0f ? v / largest : v;
}
inline bool IsFinite(vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace rtrt
