#pragma once
// Per-ray values precomputed once for a traversal: inverse direction for the slab test and the
// shear of the watertight triangle test.
#include "engine/core/float_bounds.h"
#include "engine/core/ray.h"

namespace rtrt {

struct RaySetup {
    vec3 origin;
    vec3 dir;
    vec3 invDir;           // 1/d; +-inf for +-0 components (the sign of zero is kept)
    uint32_t negative[3];  // signbit(invDir): which slab plane is near
    // Watertight test (Woop, Benthin, Wald 2013): axes permuted so that kz is the dominant one.
    int kx, ky, kz;
    float shearX, shearY, shearZ;
};

RT_HD inline RaySetup MakeRaySetup(const Ray& ray) {
    RaySetup s;
    s.origin = ray.origin;
    s.dir = ray.dir;
    s.invDir = vec3(1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z);
    for (int i = 0; i < 3; ++i) s.negative[i] = SignBit(s.invDir[i]) ? 1u : 0u;
    s.kz = MaxDimension(Abs(ray.dir));
    s.kx = s.kz + 1 == 3 ? 0 : s.kz + 1;
    s.ky = s.kx + 1 == 3 ? 0 : s.kx + 1;
    // Swapping kx and ky keeps the winding, so U, V, W keep their signs for front faces.
    if (ray.dir[s.kz] < 0.0f) {
        int t = s.kx;
        s.kx = s.ky;
        s.ky = t;
    }
    const float* d = &ray.dir.x;
    s.shearZ = 1.0f / d[s.kz];
    s.shearX = d[s.kx] * s.shearZ;
    s.shearY = d[s.ky] * s.shearZ;
    return s;
}

// A ray with NaN or infinite components, or a zero direction, hits nothing. Checked once at the
// top of a traversal so that NaN never walks the whole tree.
RT_HD inline bool IsTraceable(const Ray& ray) {
    float sum = ray.origin.x + ray.origin.y + ray.origin.z + ray.dir.x + ray.dir.y + ray.dir.z;
    bool finite = sum - sum == 0.0f;  // false for NaN and +-inf
    bool nonZero = ray.dir.x != 0.0f || ray.dir.y != 0.0f || ray.dir.z != 0.0f;
    return finite && nonZero && !(ray.tMax != ray.tMax);
}

}  // namespace rtrt
