#pragma once
// Per-ray values precomputed once for a traversal: inverse direction for the slab test and the
// shear of the watertight triangle test.
#include "engine/core/float_bounds.h"
#include "engine/core/ray.h"

namespace rtrt {

struct RaySetup {
    vec3 origin;
    vec3 dir;
    vec3 invDir;  // 1/d; +-inf for +-0 components (the sign of zero is kept)
    // Float offsets into a BvhNode of the near and far slab planes per axis: boundsMin is at
    // 0..2 and boundsMax at 4..6, so a negative direction component swaps them.
    uint32_t nearOffset[3], farOffset[3];
    // Watertight test (Woop, Benthin, Wald 2013): axes permuted so that kz is the dominant one.
    int kx, ky, kz;
    float shearX, shearY, shearZ;
    // The origin in that order: the test reads the triangle's vertices by kx, ky, kz from memory
    // but the origin from here, since indexing a ray held in GPU registers by a runtime axis
    // would put the ray in local memory.
    vec3 originK;
};

// What the slab test needs; enough for traversing a TLAS or a sphere BLAS.
RT_HD inline RaySetup MakeBoxRaySetup(const Ray& ray) {
    RaySetup s;
    s.origin = ray.origin;
    s.dir = ray.dir;
    s.invDir = vec3(1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z);
    for (int i = 0; i < 3; ++i) {
        const bool negative = SignBit(s.invDir[i]);
        s.nearOffset[i] = uint32_t(i) + (negative ? 4u : 0u);
        s.farOffset[i] = uint32_t(i) + (negative ? 0u : 4u);
    }
    return s;
}

// The slab test's values and the triangle test's shear.
RT_HD inline RaySetup MakeRaySetup(const Ray& ray) {
    RaySetup s = MakeBoxRaySetup(ray);
    s.kz = MaxDimension(Abs(ray.dir));
    s.kx = s.kz + 1 == 3 ? 0 : s.kz + 1;
    s.ky = s.kx + 1 == 3 ? 0 : s.kx + 1;
    const float* d = &ray.dir.x;
    // Swapping kx and ky keeps the winding, so U, V, W keep their signs for front faces.
    if (d[s.kz] < 0.0f) {
        int t = s.kx;
        s.kx = s.ky;
        s.ky = t;
    }
    s.shearZ = 1.0f / d[s.kz];
    const float* o = &ray.origin.x;
    s.originK = vec3(o[s.kx], o[s.ky], o[s.kz]);
    s.shearX = d[s.kx] * s.shearZ;
    s.shearY = d[s.ky] * s.shearZ;
    return s;
}

// A ray with NaN or infinite components, or a zero direction, hits nothing. Checked once at the
// top of a traversal so that NaN never walks the whole tree.
RT_HD inline bool IsTraceable(const Ray& ray) {
    constexpr float kMaxFinite = 3.40282347e+38f;
    auto finite = [](float v) { return fabsf(v) <= kMaxFinite; };  // false for NaN and +-inf
    const bool finiteRay = finite(ray.origin.x) && finite(ray.origin.y) && finite(ray.origin.z) &&
                           finite(ray.dir.x) && finite(ray.dir.y) && finite(ray.dir.z);
    const bool nonZero = ray.dir.x != 0.0f || ray.dir.y != 0.0f || ray.dir.z != 0.0f;
    return finiteRay && nonZero && !(ray.tMax != ray.tMax);
}

}  // namespace rtrt
