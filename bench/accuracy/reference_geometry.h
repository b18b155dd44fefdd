#pragma once
// The accuracy benchmark's reference intersection, in double precision on the CPU: rays,
// instance transforms, the watertight triangle test (Woop, Benthin, Wald 2013), the Ray Tracing
// Gems ch. 7 sphere test and the two-level traversal, as in engine/bvh but with every computed
// value a double. The scene itself stays as the float renderer sees it (float vertices, spheres,
// transforms and BVH boxes): the reference renders the same geometry, only more exactly.
#include <cmath>
#include <glm/glm.hpp>

#include "engine/bvh/traversal/scene_traversal.h"

namespace rtrt::reference {

using glm::dvec3;

inline constexpr double kDoubleEpsilon = 0x1p-53;  // half an ulp of 1
constexpr double GammaD(int n) { return n * kDoubleEpsilon / (1 - n * kDoubleEpsilon); }

struct RayD {
    dvec3 origin;
    dvec3 dir;
    double tMax;
};

struct HitD {
    double t;
    uint32_t instance;
    uint32_t prim;
    double b1, b2;
};

// An instance's L^-1 (instance.h), exactly as stored. The instance is defined by its float L^-1
// and position: its float ObjectToWorld is the inverse only to float precision, and a hit point
// taken to world space by it and a ray taken back would move by that much (~10^-7), far beyond
// the double error bounds, and the reference would show acne.
inline glm::dmat3 InverseLinearD(const Instance& inst) {
    glm::dmat3 inverse;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) inverse[col][row] = inst.inverseAndPosition.row[row][col];
    return inverse;
}
// The linear part L, inverted in double.
inline glm::dmat3 LinearD(const Instance& inst) { return glm::inverse(InverseLinearD(inst)); }

// World to object space as ToObjectSpace does it: subtract the instance's position first.
inline RayD ToObjectSpaceD(const RayD& ray, const Instance& inst) {
    const glm::dmat3 inverse = InverseLinearD(inst);
    return {inverse * (ray.origin - dvec3(inst.Position())), inverse * ray.dir, ray.tMax};
}

// Slab test on a float box, still conservative: the box is first widened by 8 float ulps of its
// magnitude, which covers the rounding of the float code that computed it (a sphere's centre
// +- radius, an instance's transformed corners: a few roundings each), so no box is smaller
// than the exact bounds of what it holds; the double interval is then widened by 1 + 2 gamma(3),
// which covers the rounding of the subtraction, reciprocal and product (pbrt-v4, Bounds3).
inline bool SlabTestD(const BvhNode& node, const RayD& r, dvec3 invDir, double tMax,
                      double* tEntry) {
    constexpr double kBoxSlack = 8.0 * 0x1p-24;
    double t0 = 0.0, t1 = tMax;
    for (int i = 0; i < 3; ++i) {
        const double lo = node.boundsMin[i], hi = node.boundsMax[i];
        const double slack = kBoxSlack * std::fmax(std::fabs(lo), std::fabs(hi));
        double near = (lo - slack - r.origin[i]) * invDir[i];
        double far = (hi + slack - r.origin[i]) * invDir[i];
        if (std::signbit(invDir[i])) std::swap(near, far);
        t0 = near > t0 ? near : t0;  // a NaN lane (0 * inf) is dropped
        t1 = far < t1 ? far : t1;
    }
    *tEntry = t0;
    return t0 <= t1 * (1.0 + 2.0 * GammaD(3));
}

// Either query (engine/bvh/traversal/traversal.h) over a binary BVH: kIntersect the closest hit,
// kOccluded the first; leaf(slot, tMax) tests a primitive and shrinks tMax on a nearer hit.
template <Query kQuery, typename Leaf>
bool TraverseD(const BvhNode* nodes, const RayD& r, double& tMax, Leaf&& leaf) {
    const dvec3 invDir(1.0 / r.dir.x, 1.0 / r.dir.y, 1.0 / r.dir.z);
    uint32_t stack[kBvhStackSize];
    uint32_t stackSize = 0;
    double tEntry;
    if (!SlabTestD(nodes[0], r, invDir, tMax, &tEntry)) return false;
    uint32_t current = 0;
    bool found = false;
    for (;;) {
        const BvhNode& node = nodes[current];
        if (node.IsLeaf()) {
            for (uint32_t i = 0; i < node.primCount; ++i) {
                if (leaf(node.leftFirst + i, tMax)) {
                    found = true;
                    if constexpr (kQuery == Query::kOccluded) return true;
                }
            }
        } else {
            const uint32_t left = node.leftFirst;
            double tLeft, tRight;
            const bool hitLeft = SlabTestD(nodes[left], r, invDir, tMax, &tLeft);
            const bool hitRight = SlabTestD(nodes[left + 1], r, invDir, tMax, &tRight);
            if (hitLeft && hitRight) {
                stack[stackSize++] = tLeft <= tRight ? left + 1 : left;
                current = tLeft <= tRight ? left : left + 1;
                continue;
            }
            if (hitLeft || hitRight) {
                current = hitLeft ? left : left + 1;
                continue;
            }
        }
        if (stackSize == 0) break;
        current = stack[--stackSize];
    }
    return found;
}

// The watertight test's per-ray shear, in double.
struct ShearD {
    int kx, ky, kz;
    double sx, sy, sz;
};
inline ShearD MakeShearD(dvec3 d) {
    ShearD s;
    const dvec3 a = glm::abs(d);
    s.kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    s.kx = (s.kz + 1) % 3;
    s.ky = (s.kx + 1) % 3;
    if (d[s.kz] < 0.0) std::swap(s.kx, s.ky);
    s.sz = 1.0 / d[s.kz];
    s.sx = d[s.kx] * s.sz;
    s.sy = d[s.ky] * s.sz;
    return s;
}

// triangle_intersect.h in double, with the same conservative bound on t (pbrt-v4).
inline bool IntersectTriangleD(const Triangle& tri, const RayD& r, const ShearD& sh, double tMax,
                               HitD* hit) {
    const dvec3 a = dvec3(tri.v0) - r.origin, b = dvec3(tri.v1) - r.origin,
                c = dvec3(tri.v2) - r.origin;
    const double ax = a[sh.kx] - sh.sx * a[sh.kz], ay = a[sh.ky] - sh.sy * a[sh.kz];
    const double bx = b[sh.kx] - sh.sx * b[sh.kz], by = b[sh.ky] - sh.sy * b[sh.kz];
    const double cx = c[sh.kx] - sh.sx * c[sh.kz], cy = c[sh.ky] - sh.sy * c[sh.kz];
    const double u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
    const double det = u + v + w;
    if (det == 0.0) return false;
    const double az = sh.sz * a[sh.kz], bz = sh.sz * b[sh.kz], cz = sh.sz * c[sh.kz];
    const double t = u * az + v * bz + w * cz;
    if (det < 0.0 ? t >= 0.0 : t <= 0.0) return false;
    const double invDet = 1.0 / det;
    const double maxZt = std::fmax(std::fabs(az), std::fmax(std::fabs(bz), std::fabs(cz)));
    const double maxXt = std::fmax(std::fabs(ax), std::fmax(std::fabs(bx), std::fabs(cx)));
    const double maxYt = std::fmax(std::fabs(ay), std::fmax(std::fabs(by), std::fabs(cy)));
    const double maxZ =
        std::fmax(std::fabs(a[sh.kz]), std::fmax(std::fabs(b[sh.kz]), std::fabs(c[sh.kz])));
    const double deltaZ = GammaD(3) * maxZt;
    // gamma(6): the vertex minus the double origin rounds once more than in the float test.
    const double deltaX = GammaD(6) * (maxXt + maxZ);
    const double deltaY = GammaD(6) * (maxYt + maxZ);
    const double deltaE = 2.0 * (GammaD(2) * maxXt * maxYt + deltaY * maxXt + deltaX * maxYt);
    const double maxE = std::fmax(std::fabs(u), std::fmax(std::fabs(v), std::fabs(w)));
    const double deltaT =
        3.0 * (GammaD(3) * maxE * maxZt + deltaE * maxZt + deltaZ * maxE) * std::fabs(invDet);
    const double tHit = t * invDet;
    if (tHit <= deltaT || tHit > tMax) return false;
    hit->t = tHit;
    hit->b1 = v * invDet;
    hit->b2 = w * invDet;
    return true;
}

// sphere_intersect.h (Ray Tracing Gems ch. 7) in double.
inline bool IntersectSphereD(const Sphere& s, const RayD& r, double tMax, double* tHit) {
    const dvec3 f = r.origin - dvec3(s.center);
    const double a = glm::dot(r.dir, r.dir);
    const double bPrime = -glm::dot(f, r.dir);
    const dvec3 l = f + (bPrime / a) * r.dir;
    const double r2 = double(s.radius) * double(s.radius);
    const double disc = a * (r2 - glm::dot(l, l));
    if (disc < 0.0) return false;
    const double c = glm::dot(f, f) - r2;
    const double q = bPrime + std::copysign(std::sqrt(disc), bPrime);
    double t0 = q != 0.0 ? c / q : 0.0, t1 = q / a;
    if (t0 > t1) std::swap(t0, t1);
    for (double t : {t0, t1}) {
        if (t > 0.0 && t <= tMax) {
            *tHit = t;
            return true;
        }
    }
    return false;
}

// Either query of a world-space ray within (0, ray.tMax]; kIntersect records the closest hit.
template <Query kQuery>
bool TraceSceneD(const TlasView& scene, const RayD& ray, HitD* hit) {
    double tMax = ray.tMax;
    return TraverseD<kQuery>(scene.nodes, ray, tMax, [&](uint32_t id, double& tBest) {
        const Instance& inst = scene.instances[id];
        const BlasView& blas = scene.blases[inst.blasId];
        const RayD r = ToObjectSpaceD(ray, inst);
        const ShearD shear = MakeShearD(r.dir);
        return TraverseD<kQuery>(blas.nodes, r, tBest, [&](uint32_t prim, double& t) {
            HitD h{};
            if (blas.kind == GeometryKind::kTriangles) {
                if (!IntersectTriangleD(blas.triangles[prim], r, shear, t, &h)) return false;
            } else if (!IntersectSphereD(blas.spheres[prim], r, t, &h.t)) {
                return false;
            }
            t = h.t;
            h.instance = id;
            h.prim = prim;
            *hit = h;
            return true;
        });
    });
}

}  // namespace rtrt::reference
