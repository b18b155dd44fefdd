#pragma once
// Watertight ray/triangle intersection: Woop, Benthin, Wald 2013, "Watertight Ray/Triangle
// Intersection", JCGT 2(1). Edge functions that round to exactly zero are redone in double, so
// rays through shared edges and vertices hit exactly one of the neighbours.
#include "engine/geometry/primitives.h"
#include "engine/geometry/ray_setup.h"

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
    // Vertices relative to the origin, read in the ray's permuted axis order.
    const float* v0 = &tri.v0.x;
    const float* v1 = &tri.v1.x;
    const float* v2 = &tri.v2.x;
    const float* o = &r.origin.x;
    const float aKz = v0[r.kz] - o[r.kz], bKz = v1[r.kz] - o[r.kz], cKz = v2[r.kz] - o[r.kz];
    const float ax = (v0[r.kx] - o[r.kx]) - r.shearX * aKz;
    const float ay = (v0[r.ky] - o[r.ky]) - r.shearY * aKz;
    const float bx = (v1[r.kx] - o[r.kx]) - r.shearX * bKz;
    const float by = (v1[r.ky] - o[r.ky]) - r.shearY * bKz;
    const float cx = (v2[r.kx] - o[r.kx]) - r.shearX * cKz;
    const float cy = (v2[r.ky] - o[r.ky]) - r.shearY * cKz;
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
    const float az = r.shearZ * aKz;
    const float bz = r.shearZ * bKz;
    const float cz = r.shearZ * cKz;
    const float t = u * az + v * bz + w * cz;
    // t and det share a sign for hits in front of the origin.
    if (det < 0.0f ? t >= 0.0f : t <= 0.0f) return false;
    // Beyond tMax, compared without dividing. The slack covers the rounding of both sides, so
    // that this early out never rejects a hit whose divided t rounds to <= tMax (the exact test
    // is the last line): without it a hit one ulp nearer than tMax could be rejected or not
    // depending on rounding, and the closest of several hits at nearly equal t depended on the
    // order the triangles were tested in (tests/robust, overlapping TLAS instances).
    if (fabsf(t) > tMax * fabsf(det) * (1.0f + 2.0f * Gamma(3))) return false;
    const float invDet = 1.0f / det;
    // Reject t that rounding alone could have made positive: a ray leaving a surface must not hit
    // that surface again (pbrt-v4, "Ensure that computed triangle t is conservatively greater
    // than zero": bounds on the error of the sheared coordinates, edge functions and t).
    const float maxZt = MaxOrKeep(fabsf(az), MaxOrKeep(fabsf(bz), fabsf(cz)));
    const float maxXt = MaxOrKeep(fabsf(ax), MaxOrKeep(fabsf(bx), fabsf(cx)));
    const float maxYt = MaxOrKeep(fabsf(ay), MaxOrKeep(fabsf(by), fabsf(cy)));
    const float deltaZ = Gamma(3) * maxZt;
    // The shear x' = x - shearX z errs by at most gamma(5) (|x| + |z|) with the unscaled z
    // (|shearX| <= 1: kz is the dominant axis). pbrt-v4 uses the z already scaled by 1/d_kz,
    // which bounds it only for |d_kz| <= 1: object-space directions are not unit length here,
    // so a large instance (short direction) rejected every hit and a small one (long direction)
    // under-estimated the error (tests/robust: direction scale invariance).
    const float maxZ = MaxOrKeep(fabsf(aKz), MaxOrKeep(fabsf(bKz), fabsf(cKz)));
    const float deltaX = Gamma(5) * (maxXt + maxZ);
    const float deltaY = Gamma(5) * (maxYt + maxZ);
    const float deltaE = 2.0f * (Gamma(2) * maxXt * maxYt + deltaY * maxXt + deltaX * maxYt);
    const float maxE = MaxOrKeep(fabsf(u), MaxOrKeep(fabsf(v), fabsf(w)));
    const float deltaT =
        3.0f * (Gamma(3) * maxE * maxZt + deltaE * maxZt + deltaZ * maxE) * fabsf(invDet);
    if (t * invDet <= deltaT) return false;
    hit->t = t * invDet;
    hit->b1 = v * invDet;
    hit->b2 = w * invDet;
    return hit->t <= tMax;
}

}  // namespace rtrt
