#pragma once
// Watertight ray/triangle intersection: Woop, Benthin, Wald 2013, "Watertight Ray/Triangle
// Intersection", JCGT 2(1). Edge functions that round to exactly zero are redone in double, so
// rays through shared edges and vertices hit exactly one of the neighbours.
#include "engine/bvh/primitives.h"
#include "engine/bvh/ray_setup.h"

namespace rtrt {

struct TriangleHit {
    float t;
    float b1, b2;  // barycentrics of v1 and v2
};

// a*b - c*d without FMA contraction: the three edge functions must round the same way for both
// triangles sharing an edge, which a fused multiply-add would break.
RT_HD inline float CrossDiffNoContract(float a, float b, float c, float d) {
#if defined(__CUDA_ARCH__)
    return __fsub_rn(__fmul_rn(a, b), __fmul_rn(c, d));
#else
    return a * b - c * d;  // host code is compiled with -ffp-contract=off (engine/core)
#endif
}

RT_HD inline bool IntersectTriangle(const Triangle& tri, const RaySetup& r, float tMax,
                                    TriangleHit* hit) {
    const vec3 a = tri.v0 - r.origin;
    const vec3 b = tri.v1 - r.origin;
    const vec3 c = tri.v2 - r.origin;
    const float ax = a[r.kx] - r.shearX * a[r.kz];
    const float ay = a[r.ky] - r.shearY * a[r.kz];
    const float bx = b[r.kx] - r.shearX * b[r.kz];
    const float by = b[r.ky] - r.shearY * b[r.kz];
    const float cx = c[r.kx] - r.shearX * c[r.kz];
    const float cy = c[r.ky] - r.shearY * c[r.kz];
    float u = CrossDiffNoContract(cx, by, cy, bx);
    float v = CrossDiffNoContract(ax, cy, ay, cx);
    float w = CrossDiffNoContract(bx, ay, by, ax);
    if (u == 0.0f || v == 0.0f || w == 0.0f) {
        u = float(double(cx) * double(by) - double(cy) * double(bx));
        v = float(double(ax) * double(cy) - double(ay) * double(cx));
        w = float(double(bx) * double(ay) - double(by) * double(ax));
    }
    if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return false;
    const float det = u + v + w;
    if (det == 0.0f) return false;
    const float az = r.shearZ * a[r.kz];
    const float bz = r.shearZ * b[r.kz];
    const float cz = r.shearZ * c[r.kz];
    const float t = u * az + v * bz + w * cz;
    // t and det share a sign for hits in front of the origin; compare without dividing.
    if (det < 0.0f ? (t >= 0.0f || t < tMax * det) : (t <= 0.0f || t > tMax * det)) return false;
    const float invDet = 1.0f / det;
    // Reject t that rounding alone could have made positive: a ray leaving a surface must not hit
    // that surface again (pbrt-v4, "Ensure that computed triangle t is conservatively greater
    // than zero": bounds on the error of the sheared coordinates, edge functions and t).
    const float maxZt = fmaxf(fabsf(az), fmaxf(fabsf(bz), fabsf(cz)));
    const float maxXt = fmaxf(fabsf(ax), fmaxf(fabsf(bx), fabsf(cx)));
    const float maxYt = fmaxf(fabsf(ay), fmaxf(fabsf(by), fabsf(cy)));
    const float deltaZ = Gamma(3) * maxZt;
    const float deltaX = Gamma(5) * (maxXt + maxZt);
    const float deltaY = Gamma(5) * (maxYt + maxZt);
    const float deltaE = 2.0f * (Gamma(2) * maxXt * maxYt + deltaY * maxXt + deltaX * maxYt);
    const float maxE = fmaxf(fabsf(u), fmaxf(fabsf(v), fabsf(w)));
    const float deltaT =
        3.0f * (Gamma(3) * maxE * maxZt + deltaE * maxZt + deltaZ * maxE) * fabsf(invDet);
    if (t * invDet <= deltaT) return false;
    hit->t = t * invDet;
    hit->b1 = v * invDet;
    hit->b2 = w * invDet;
    return hit->t <= tMax;
}

}  // namespace rtrt
