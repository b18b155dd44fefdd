#pragma once
// Watertight ray/triangle intersection: Woop, Benthin, Wald 2013, "Watertight Ray/Triangle
// Intersection", JCGT 2(1). Edge functions that round to exactly zero are redone in double, so
// rays through shared edges and vertices hit exactly one of the neighbours. Hits whose t is within
// its error bound of 0 are decided again on the triangle's plane (NearHitOnPlane).
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

// A hit whose t from the watertight test lies within that test's error bound of 0: in front of
// the origin, or behind it and moved forward by rounding (a ray leaving this very triangle, or a
// coplanar neighbour)? The plane's distance decides it with a much smaller bound: t =
// n.(v0 - o) / n.d, n = (v1 - v0) x (v2 - v0), where each difference and product errs by one
// rounding, so numerator and denominator err by at most gamma(8) times the same sums over
// absolute values: ~1e-6 of the triangle's size, against the sheared test's ~1e-5 (its bound
// multiplies the errors of the edge functions and of the sheared depths). A sign that the error
// could flip is no hit: the origin lies in the plane as far as float can tell. Float, not double:
// a double path in the triangle test, even one rarely taken, slowed the whole GPU trace
// (bench/results/numerics-h200-2026-12-02.txt).
RT_HD inline bool NearHitOnPlane(const Triangle& tri, const RaySetup& r, float* t) {
    const vec3 e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
    const vec3 toV0 = tri.v0 - r.origin;
    const vec3 n = glm::cross(e1, e2);
    const vec3 a1 = Abs(e1), a2 = Abs(e2);
    const vec3 nAbs(a1.y * a2.z + a1.z * a2.y, a1.z * a2.x + a1.x * a2.z,
                    a1.x * a2.y + a1.y * a2.x);
    const float num = glm::dot(n, toV0), den = glm::dot(n, r.dir);
    const float numError = Gamma(8) * glm::dot(nAbs, Abs(toV0));
    const float denError = Gamma(8) * glm::dot(nAbs, Abs(r.dir));
    if (!(fabsf(num) > numError) || !(fabsf(den) > denError)) return false;
    *t = num / den;
    return *t > 0.0f;
}

// kRefineNearHits = false rejects every hit within the error bound, as pbrt-v4 does: no
// self-hits either, but real hits nearer than the bound (1e-5 for a unit triangle) are lost, so a
// contact shadow 1e-5 under an occluder is lit (the accuracy benchmark's "no plane test").
// Inlined into the CPU's leaf loops: left to itself the compiler calls it there.
template <bool kRefineNearHits = true>
RT_HOST_ALWAYS_INLINE RT_HD inline bool IntersectTriangle(const Triangle& tri, const RaySetup& r,
                                                          float tMax, TriangleHit* hit) {
    // Vertices relative to the origin, read in the ray's permuted axis order.
    const float* v0 = &tri.v0.x;
    const float* v1 = &tri.v1.x;
    const float* v2 = &tri.v2.x;
    const vec3 o = r.originK;
    const float aKz = v0[r.kz] - o.z, bKz = v1[r.kz] - o.z, cKz = v2[r.kz] - o.z;
    const float ax = (v0[r.kx] - o.x) - r.shearX * aKz;
    const float ay = (v0[r.ky] - o.y) - r.shearY * aKz;
    const float bx = (v1[r.kx] - o.x) - r.shearX * bKz;
    const float by = (v1[r.ky] - o.y) - r.shearY * bKz;
    const float cx = (v2[r.kx] - o.x) - r.shearX * cKz;
    const float cy = (v2[r.ky] - o.y) - r.shearY * cKz;
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
    // The bound on the rounding error of t (pbrt-v4, "Ensure that computed triangle t is
    // conservatively greater than zero": bounds on the error of the sheared coordinates, edge
    // functions and t), here still multiplied by |det|. A t within it of 0 may be a ray leaving
    // this very surface, which must not hit it again, or a real hit just in front of the origin:
    // 1e-5 for a unit triangle seen by a ray whose dominant axis is not the normal's, so a
    // contact shadow under an occluder 1e-5 above was lit and a ray starting 1e-5 from a surface
    // missed it. The plane test decides those (kRefineNearHits).
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
    const float deltaTimesDet = 3.0f * (Gamma(3) * maxE * maxZt + deltaE * maxZt + deltaZ * maxE);
    // t with the sign of t / det, so that both comparisons below need no division.
    const float tSigned = det < 0.0f ? -t : t;
    const float absDet = fabsf(det);
    const float invDet = 1.0f / det;
    if (tSigned > deltaTimesDet) {
        // Beyond tMax, compared without dividing. The slack covers the rounding of both sides,
        // so that this early out never rejects a hit whose divided t rounds to <= tMax (the
        // exact test is the last line): without it a hit one ulp nearer than tMax could be
        // rejected or not depending on rounding, and the closest of several hits at nearly
        // equal t depended on the order the triangles were tested in (tests/robust, overlapping
        // TLAS instances). It applies only outside the band of the plane test, whose answer
        // must not depend on the tMax it is asked with, for the same reason.
        if (tSigned > tMax * absDet * (1.0f + 2.0f * Gamma(3))) return false;
        hit->t = t * invDet;
    } else {
        // Behind the origin beyond the bound, or no plane test: no hit (NaN included).
        if (!kRefineNearHits || !(tSigned >= -deltaTimesDet)) return false;
        if (!NearHitOnPlane(tri, r, &hit->t)) return false;
    }
    hit->b1 = v * invDet;
    hit->b2 = w * invDet;
    return hit->t <= tMax;
}

}  // namespace rtrt
