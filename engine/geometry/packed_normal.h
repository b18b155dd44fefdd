#pragma once
// Unit normals in 32 bits: the octahedral mapping (Cigolle et al. 2014, "A Survey of Efficient
// Representations for Independent Unit Vectors", JCGT 3(2)) with two 16-bit signed-normalised
// components. The encoder tries the four roundings of the two components and keeps the one that
// decodes closest to the input (the paper's "precise" variant), so that the angle between a
// normal and its decoding stays below 5e-5 radians.
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
    return v * (1.0f / sqrtf(glm::dot(v, v)));
}

// N need not be unit length; a zero or non-finite N packs as +z.
RT_HD inline uint32_t PackNormal(vec3 n) {
    using namespace packed_normal_detail;
    const float l1 = fabsf(n.x) + fabsf(n.y) + fabsf(n.z);
    if (!(l1 > 0.0f) || !(l1 < INFINITY)) return 0;  // (0, 0) decodes to +z
    float x = n.x / l1, y = n.y / l1;
    if (n.z < 0.0f) {
        const float fx = (1.0f - fabsf(y)) * SignNotZero(x);
        const float fy = (1.0f - fabsf(x)) * SignNotZero(y);
        x = fx;
        y = fy;
    }
    const vec3 unit = n * (1.0f / sqrtf(glm::dot(n, n)));
    const float sx = fminf(fmaxf(x, -1.0f), 1.0f) * 32767.0f;
    const float sy = fminf(fmaxf(y, -1.0f), 1.0f) * 32767.0f;
    // Closest by distance, not by dot product: near 1, float dot products of such close
    // directions are all equal.
    uint32_t best = 0;
    float bestDistance = INFINITY;
    for (int k = 0; k < 4; ++k) {
        const int qx = int((k & 1) ? ceilf(sx) : floorf(sx));
        const int qy = int((k & 2) ? ceilf(sy) : floorf(sy));
        const uint32_t packed = uint32_t(uint16_t(int16_t(qx))) | uint32_t(uint16_t(int16_t(qy)))
                                                                      << 16;
        const vec3 error = UnpackNormal(packed) - unit;
        const float distance = glm::dot(error, error);
        if (distance < bestDistance) {
            bestDistance = distance;
            best = packed;
        }
    }
    return best;
}

}  // namespace rtrt
