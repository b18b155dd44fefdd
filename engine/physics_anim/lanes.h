#pragma once
// Eight floats computed as one: the contact solver's rows (contact_rows.h) solve eight contacts
// of eight different manifolds at once, and the broad phase tests a box against eight others. GCC's
// vector extension gives the arithmetic (+ - * / and comparisons lane by lane, ?: as a per-lane
// select) on any x86 target: AVX registers where the build has them, pairs of SSE registers where
// it does not.
#include <immintrin.h>

#include <cstdint>

namespace rtrt::physics {

inline constexpr int kLanes = 8;
using Lanes = float __attribute__((vector_size(kLanes * sizeof(float))));
using LaneMask = int32_t __attribute__((vector_size(kLanes * sizeof(int32_t))));

inline Lanes Splat(float x) { return Lanes{x, x, x, x, x, x, x, x}; }

inline Lanes Select(LaneMask mask, Lanes yes, Lanes no) { return mask ? yes : no; }

inline Lanes Max(Lanes a, Lanes b) { return a > b ? a : b; }

// fabsf and copysignf lane by lane, on the sign bit as they work.
inline Lanes Abs(Lanes x) {
    return reinterpret_cast<Lanes>(reinterpret_cast<LaneMask>(x) & 0x7fffffff);
}
inline Lanes CopySign(Lanes magnitude, Lanes sign) {
    const LaneMask signBit = reinterpret_cast<LaneMask>(sign) & static_cast<int32_t>(0x80000000u);
    return reinterpret_cast<Lanes>((reinterpret_cast<LaneMask>(magnitude) & 0x7fffffff) | signBit);
}

inline Lanes Sqrt(Lanes x) {
#if defined(__AVX__)
    return reinterpret_cast<Lanes>(_mm256_sqrt_ps(reinterpret_cast<__m256>(x)));
#else
    Lanes out;
    for (int l = 0; l < kLanes; ++l) out[l] = __builtin_sqrtf(x[l]);
    return out;
#endif
}

// Eight consecutive values from p, which need not be aligned.
inline Lanes LoadLanes(const float* p) {
    Lanes v;
    __builtin_memcpy(&v, p, sizeof v);
    return v;
}
inline LaneMask LoadMask(const int32_t* p) {
    LaneMask v;
    __builtin_memcpy(&v, p, sizeof v);
    return v;
}

// Bit l set where lane l of mask is.
inline uint32_t LaneBits(LaneMask mask) {
#if defined(__AVX__)
    return static_cast<uint32_t>(_mm256_movemask_ps(reinterpret_cast<__m256>(mask)));
#else
    uint32_t bits = 0;
    for (int l = 0; l < kLanes; ++l) bits |= (mask[l] != 0 ? 1u : 0u) << l;
    return bits;
#endif
}

inline bool AnyLane(LaneMask mask) {
    for (int l = 0; l < kLanes; ++l) {
        if (mask[l] != 0) return true;
    }
    return false;
}

// A vector of lanes, and a column-major 3x3 matrix of lanes (m[column][row], as glm).
struct Lanes3 {
    Lanes x, y, z;
};
struct Lanes33 {
    Lanes3 column[3];
};

inline Lanes3 operator+(const Lanes3& a, const Lanes3& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Lanes3 operator-(const Lanes3& a, const Lanes3& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Lanes3 operator*(Lanes s, const Lanes3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline Lanes Dot(const Lanes3& a, const Lanes3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Lanes3 Cross(const Lanes3& a, const Lanes3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Lanes3 Select3(LaneMask mask, const Lanes3& yes, const Lanes3& no) {
    return {Select(mask, yes.x, no.x), Select(mask, yes.y, no.y), Select(mask, yes.z, no.z)};
}
inline Lanes33 operator+(const Lanes33& a, const Lanes33& b) {
    return {{a.column[0] + b.column[0], a.column[1] + b.column[1], a.column[2] + b.column[2]}};
}
inline Lanes3 operator*(const Lanes33& m, const Lanes3& v) {
    return {m.column[0].x * v.x + m.column[1].x * v.y + m.column[2].x * v.z,
            m.column[0].y * v.x + m.column[1].y * v.y + m.column[2].y * v.z,
            m.column[0].z * v.x + m.column[1].z * v.y + m.column[2].z * v.z};
}

}  // namespace rtrt::physics
