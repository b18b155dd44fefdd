#pragma once
// Unit normals in 32 bits: the octahedral mapping (Cigolle et al. 2014, "A Survey of Efficient
// Representations for Independent Unit Vectors", JCGT 3(2)) with two 16-bit signed-normalised
// components. The precise encoder tries the four roundings of the two components and keeps the
// one that decodes closest to the input (the paper's "precise" variant), so that the angle
// between a normal and its decoding stays below 5e-5 radians; the rounded one stays below 1e-4.
#include <cmath>
#include <cstdint>

#include "engine/core/math.h"

namespace rtrt {

namespace packed_normal_detail {

RT_HD inline float SignNotZero(float v) { return v >= 0.0f ? 1.0f : -1.0f; }

// The octahedron's square [-1, 1]^2 back onto the unit sphere (not yet normalised).
RT_HD inline vec3 OctahedronToSphere(float x, float y) {
    vec3 v(x, y, 1.0f - fabsf(x) - fabsf(y));
    if (v.z < 0.0f) {
        const float fx = (1.0f - fabsf(y)) * SignNotZero(x);
        const float fy = (1.0f - fabsf(x)) * SignNotZero(y);
        v.x = fx;
        v.y = fy;
    }
    return v;
}

RT_HD inline float Snorm16ToFloat(uint32_t bits) {
    const float v = float(int16_t(uint16_t(bits))) * (1.0f / 32767.0f);
    return v < -1.0f ? -1.0f : v;
}

}  // namespace packed_normal_detail

RT_HD inline vec3 UnpackNormal(uint32_t packed) {
    using namespace packed_normal_detail;
    const vec3 v = OctahedronToSphere(Snorm16ToFloat(packed), Snorm16ToFloat(packed >> 16));
#if defined(__CUDA_ARCH__)
    // One hardware instruction (within 2 ulp) where the IEEE square root and division are
    // sequences: the tracer decodes three normals per shaded hit.
    return v * rsqrtf(glm::dot(v, v));
#else
    return v * (1.0f / sqrtf(glm::dot(v, v)));
#endif
}

namespace packed_normal_detail {

// N's point on the octahedron's square, scaled to the snorm16 range; false for a zero or
// non-finite N.
RT_HD inline bool OctahedronOf(vec3 n, float& sx, float& sy) {
    const float l1 = fabsf(n.x) + fabsf(n.y) + fabsf(n.z);
    if (!(l1 > 0.0f) || !(l1 < INFINITY)) return false;
    float x = n.x / l1, y = n.y / l1;
    if (n.z < 0.0f) {
        const float fx = (1.0f - fabsf(y)) * SignNotZero(x);
        const float fy = (1.0f - fabsf(x)) * SignNotZero(y);
        x = fx;
        y = fy;
    }
    // Comparisons rather than fminf/fmaxf, which are library calls on x86 without -ffast-math.
    sx = (x < -1.0f ? -1.0f : x > 1.0f ? 1.0f : x) * 32767.0f;
    sy = (y < -1.0f ? -1.0f : y > 1.0f ? 1.0f : y) * 32767.0f;
    return true;
}

RT_HD inline uint32_t Snorm16Pair(int qx, int qy) {
    return uint32_t(uint16_t(int16_t(qx))) | uint32_t(uint16_t(int16_t(qy))) << 16;
}

}  // namespace packed_normal_detail

// N need not be unit length; a zero or non-finite N packs as +z. The precise encoder, for BLAS
// builds.
RT_HD inline uint32_t PackNormal(vec3 n) {
    using namespace packed_normal_detail;
    float sx, sy;
    if (!OctahedronOf(n, sx, sy)) return 0;  // (0, 0) decodes to +z
    const vec3 unit = n * (1.0f / sqrtf(glm::dot(n, n)));
    // Closest by distance, not by dot product: near 1, float dot products of such close
    // directions are all equal.
    uint32_t best = 0;
    float bestDistance = INFINITY;
    for (int k = 0; k < 4; ++k) {
        const uint32_t packed = Snorm16Pair(int((k & 1) ? ceilf(sx) : floorf(sx)),
                                            int((k & 2) ? ceilf(sy) : floorf(sy)));
        const vec3 error = UnpackNormal(packed) - unit;
        const float distance = glm::dot(error, error);
        if (distance < bestDistance) {
            bestDistance = distance;
            best = packed;
        }
    }
    return best;
}

// The same with each component rounded to the nearest step: a quarter of the work, for normals
// packed every frame (deforming meshes), within 1e-4 radians.
RT_HD inline uint32_t PackNormalRounded(vec3 n) {
    using namespace packed_normal_detail;
    float sx, sy;
    if (!OctahedronOf(n, sx, sy)) return 0;
    return Snorm16Pair(int(rintf(sx)), int(rintf(sy)));
}

}  // namespace rtrt
