#pragma once
// An orthonormal basis around a unit vector, on the CPU and on the GPU (the contact solvers build
// their friction directions with it, so both must get the same bits).
#include "engine/core/math.h"

namespace rtrt::physics {

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited": (u, v) with u x v = n for unit n,
// without a branch on n's direction.
RT_HD inline void OrthonormalBasis(vec3 n, vec3& u, vec3& v) {
    const float sign = copysignf(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    u = vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    v = vec3(b, sign + n.y * n.y * a, -n.y);
}

}  // namespace rtrt::physics
