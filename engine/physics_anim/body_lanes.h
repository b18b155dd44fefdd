#pragma once
// The bodies of a row of contacts as lanes (lanes.h): the solver's state of eight bodies, picked by
// slot, gathered into one vector per field and scattered back, with 8x8 transposes where the build
// has AVX.
#include <immintrin.h>

#include <cstddef>
#include <cstdint>
#include <span>

#include "engine/physics_anim/lanes.h"
#include "engine/physics_anim/solver_types.h"

namespace rtrt::physics {

// The velocities and inverse masses of one body per lane.
struct BodyLanes {
    Lanes3 velocity;
    Lanes3 angularVelocity;
    Lanes invMass;
    Lanes33 invInertia;
};

// A SolverBody is 16 floats: velocity, invMass, angularVelocity, then the inertia's columns.
static_assert(sizeof(SolverBody) == 16 * sizeof(float));
static_assert(offsetof(SolverBody, angularVelocity) == 4 * sizeof(float));
static_assert(offsetof(SolverBody, invInertia) == 7 * sizeof(float));

#if defined(__AVX__)
// rows[i][j] -> rows[j][i], for eight rows of eight floats.
[[gnu::always_inline]] inline void Transpose8(__m256 (&rows)[8]) {
    __m256 t[8];
    __m256 s[8];
    for (int i = 0; i < 4; ++i) {
        t[2 * i] = _mm256_unpacklo_ps(rows[2 * i], rows[2 * i + 1]);
        t[2 * i + 1] = _mm256_unpackhi_ps(rows[2 * i], rows[2 * i + 1]);
    }
    for (int i = 0; i < 2; ++i) {
        s[4 * i] = _mm256_shuffle_ps(t[4 * i], t[4 * i + 2], _MM_SHUFFLE(1, 0, 1, 0));
        s[4 * i + 1] = _mm256_shuffle_ps(t[4 * i], t[4 * i + 2], _MM_SHUFFLE(3, 2, 3, 2));
        s[4 * i + 2] = _mm256_shuffle_ps(t[4 * i + 1], t[4 * i + 3], _MM_SHUFFLE(1, 0, 1, 0));
        s[4 * i + 3] = _mm256_shuffle_ps(t[4 * i + 1], t[4 * i + 3], _MM_SHUFFLE(3, 2, 3, 2));
    }
    for (int i = 0; i < 4; ++i) {
        rows[i] = _mm256_permute2f128_ps(s[i], s[i + 4], 0x20);
        rows[i + 4] = _mm256_permute2f128_ps(s[i], s[i + 4], 0x31);
    }
}
#endif

// Eight consecutive floats of each of eight records as eight lanes vectors: element f of lane l is
// records[l][f]. The records need not be aligned.
[[gnu::always_inline]] inline void GatherColumns(const float* const (&records)[kLanes],
                                                 Lanes (&out)[8]) {
#if defined(__AVX__)
    __m256 rows[8];
    for (int l = 0; l < kLanes; ++l) rows[l] = _mm256_loadu_ps(records[l]);
    Transpose8(rows);
    for (int f = 0; f < 8; ++f) out[f] = reinterpret_cast<const Lanes&>(rows[f]);
#else
    for (int l = 0; l < kLanes; ++l) {
        for (int f = 0; f < 8; ++f) out[f][l] = records[l][f];
    }
#endif
}

// The bodies' 16 floats as 16 lanes vectors: element f of lane l is float f of body slots[l].
[[gnu::always_inline]] inline void GatherFloats(std::span<const SolverBody> bodies,
                                                const uint32_t (&slots)[kLanes], Lanes (&out)[16]) {
    for (int half = 0; half < 2; ++half) {
        const float* records[kLanes];
        for (int l = 0; l < kLanes; ++l) {
            records[l] = reinterpret_cast<const float*>(&bodies[slots[l]]) + 8 * half;
        }
        GatherColumns(records, reinterpret_cast<Lanes(&)[8]>(out[8 * half]));
    }
}

[[gnu::always_inline]] inline BodyLanes Gather(std::span<const SolverBody> bodies,
                                               const uint32_t (&slots)[kLanes]) {
    Lanes f[16];
    GatherFloats(bodies, slots, f);
    BodyLanes out;
    out.velocity = {f[0], f[1], f[2]};
    out.invMass = f[3];
    out.angularVelocity = {f[4], f[5], f[6]};
    for (int c = 0; c < 3; ++c)
        out.invInertia.column[c] = {f[7 + 3 * c], f[8 + 3 * c], f[9 + 3 * c]};
    return out;
}

// Writes the velocities of the active lanes' moving bodies (a body that does not move may be read
// by other threads at the same time, and its velocities did not change). The first eight floats
// of a body go back whole: its inverse mass and first inertia entry are unchanged.
[[gnu::always_inline]] inline void Scatter(std::span<SolverBody> bodies,
                                           const uint32_t (&slots)[kLanes], uint32_t activeLanes,
                                           const BodyLanes& in) {
#if defined(__AVX__)
    const Lanes first[8] = {in.velocity.x,        in.velocity.y,
                            in.velocity.z,        in.invMass,
                            in.angularVelocity.x, in.angularVelocity.y,
                            in.angularVelocity.z, in.invInertia.column[0].x};
    __m256 rows[8];
    for (int f = 0; f < 8; ++f) rows[f] = reinterpret_cast<const __m256&>(first[f]);
    Transpose8(rows);
    for (int l = 0; l < kLanes; ++l) {
        if ((activeLanes >> l & 1u) == 0 || !(in.invMass[l] > 0.0f)) continue;
        _mm256_store_ps(reinterpret_cast<float*>(&bodies[slots[l]]), rows[l]);
    }
#else
    for (int l = 0; l < kLanes; ++l) {
        if ((activeLanes >> l & 1u) == 0 || !(in.invMass[l] > 0.0f)) continue;
        SolverBody& s = bodies[slots[l]];
        s.velocity = vec3(in.velocity.x[l], in.velocity.y[l], in.velocity.z[l]);
        s.angularVelocity =
            vec3(in.angularVelocity.x[l], in.angularVelocity.y[l], in.angularVelocity.z[l]);
    }
#endif
}

// A PseudoVelocity is 8 floats: linear, angular, two of padding.
static_assert(sizeof(PseudoVelocity) == 8 * sizeof(float));
static_assert(offsetof(PseudoVelocity, angular) == 3 * sizeof(float));

struct PseudoLanes {
    Lanes3 linear;
    Lanes3 angular;
};

[[gnu::always_inline]] inline PseudoLanes GatherPseudo(std::span<const PseudoVelocity> pseudo,
                                                       const uint32_t (&slots)[kLanes]) {
#if defined(__AVX__)
    __m256 rows[8];
    for (int l = 0; l < kLanes; ++l) {
        rows[l] = _mm256_load_ps(reinterpret_cast<const float*>(&pseudo[slots[l]]));
    }
    Transpose8(rows);
    Lanes f[8];
    for (int i = 0; i < 8; ++i) f[i] = reinterpret_cast<const Lanes&>(rows[i]);
#else
    Lanes f[8];
    for (int l = 0; l < kLanes; ++l) {
        const float* p = reinterpret_cast<const float*>(&pseudo[slots[l]]);
        for (int i = 0; i < 6; ++i) f[i][l] = p[i];
    }
#endif
    return {{f[0], f[1], f[2]}, {f[3], f[4], f[5]}};
}

// Writes the pseudo velocities of the active lanes' moving bodies (moving: invMass > 0).
[[gnu::always_inline]] inline void ScatterPseudo(std::span<PseudoVelocity> pseudo,
                                                 const uint32_t (&slots)[kLanes],
                                                 uint32_t activeLanes, const Lanes& invMass,
                                                 const PseudoLanes& in) {
#if defined(__AVX__)
    const Lanes zero = Splat(0.0f);
    const Lanes f[8] = {in.linear.x,  in.linear.y,  in.linear.z, in.angular.x,
                        in.angular.y, in.angular.z, zero,        zero};
    __m256 rows[8];
    for (int i = 0; i < 8; ++i) rows[i] = reinterpret_cast<const __m256&>(f[i]);
    Transpose8(rows);
    for (int l = 0; l < kLanes; ++l) {
        if ((activeLanes >> l & 1u) == 0 || !(invMass[l] > 0.0f)) continue;
        _mm256_store_ps(reinterpret_cast<float*>(&pseudo[slots[l]]), rows[l]);
    }
#else
    for (int l = 0; l < kLanes; ++l) {
        if ((activeLanes >> l & 1u) == 0 || !(invMass[l] > 0.0f)) continue;
        PseudoVelocity& p = pseudo[slots[l]];
        p.linear = vec3(in.linear.x[l], in.linear.y[l], in.linear.z[l]);
        p.angular = vec3(in.angular.x[l], in.angular.y[l], in.angular.z[l]);
    }
#endif
}

}  // namespace rtrt::physics
