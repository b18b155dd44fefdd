#pragma once
// Two-level traversal: the TLAS over instances, then each reached instance's BLAS in object
// space. Object-space directions are not renormalised, so t means the same in both spaces.
//
// This is the nested form: a BLAS traversal in each reached TLAS leaf. The CPU uses it with the
// triangle BLASes' 4-wide SSE collapse; the GPU uses it for scenes of few instances, where the
// ray spends its time in one tight BLAS loop. Scenes of many instances may run the single loop of
// two_level_traversal.h on the GPU (see kFeatureManyInstances); both forms find the same hits.
#include "engine/bvh/traversal/two_level_traversal.h"
#include "engine/geometry/primitive_tests.h"

// The CPU back end traverses triangle BLASes through their 4-wide collapse (SSE); the GPU and the
// heatmap's node counts use the binary BVH.
#if !defined(__CUDACC__)
#include "engine/bvh/traversal/bvh4_traversal.h"
#include "engine/geometry/triangle_intersect4.h"
#define RTRT_HOST_WIDE_BVH 1
#endif

namespace rtrt {

#if defined(RTRT_HOST_WIDE_BVH)
// Whether Tests tests triangles with production's watertight test, which the CPU then runs on
// up to four triangles of a leaf at once (triangle_intersect4.h) with the same answers.
template <class Tests>
inline constexpr bool kWatertightTriangles =
    &Tests::IntersectTriangle == &PrimitiveTests::IntersectTriangle;
#endif

// The world-space ray against one instance's BLAS. Tests supplies the primitive tests
// (primitive_tests.h); spheres are tested on the exact object-space ray (ToObjectSpaceExact).
template <class Tests = PrimitiveTests>
RT_HD inline bool IntersectBlas(const BlasView& blas, const Instance& inst, const Ray& ray,
                                float& tMax, SceneHit* hit, TraversalStats* stats) {
    const Ray objectRay = ToObjectSpace(ray, inst);
    if (blas.kind == GeometryKind::kTriangles) {
        const RaySetup setup = MakeRaySetup(objectRay);
        auto intersect = [&](uint32_t slot, float& tBest) {
            TriangleHit h;
            if (!Tests::IntersectTriangle(blas.triangles[slot], setup, tBest, &h)) return false;
            tBest = h.t;
            hit->t = h.t;
            hit->prim = slot;
            hit->b1 = h.b1;
            hit->b2 = h.b2;
            return true;
        };
#if defined(RTRT_HOST_WIDE_BVH)
        if constexpr (kWatertightTriangles<Tests>) {
            if (blas.nodes4 && !stats) {
                auto intersectLeaf = [&](uint32_t first, uint32_t count, float& tBest) {
                    TriangleHit h;
                    const int i = ClosestTriangle(blas.triangles + first, count, setup, tBest, &h);
                    if (i < 0) return false;
                    hit->t = h.t;
                    hit->prim = first + uint32_t(i);
                    hit->b1 = h.b1;
                    hit->b2 = h.b2;
                    return true;
                };
                return Traverse4<Query::kIntersect>(blas.nodes4, setup, tMax, intersectLeaf);
            }
        }
        if (blas.nodes4 && !stats)
            return Traverse4<Query::kIntersect>(blas.nodes4, setup, tMax, intersect);
#endif
        return Traverse<Query::kIntersect>(blas.nodes, setup, tMax, intersect, stats);
    }
    const RaySetup setup = MakeBoxRaySetup(objectRay);
    const SphereRay sphereRay = ToObjectSpaceExact(ray, inst);
    return Traverse<Query::kIntersect>(
        blas.nodes, setup, tMax,
        [&](uint32_t slot, float& tBest) {
            float t;
            if (!Tests::IntersectSphere(blas.spheres[slot], sphereRay, tBest, &t)) return false;
            tBest = t;
            hit->t = t;
            hit->prim = slot;
            hit->b1 = hit->b2 = 0.0f;
            return true;
        },
        stats);
}

template <class Tests = PrimitiveTests>
RT_HD inline bool OccludedBlas(const BlasView& blas, const Instance& inst, const Ray& ray,
                               float tMax, TraversalStats* stats) {
    const Ray objectRay = ToObjectSpace(ray, inst);
    if (blas.kind == GeometryKind::kTriangles) {
        const RaySetup setup = MakeRaySetup(objectRay);
        auto occludes = [&](uint32_t slot, float tLimit) {
            TriangleHit h;
            return Tests::IntersectTriangle(blas.triangles[slot], setup, tLimit, &h);
        };
#if defined(RTRT_HOST_WIDE_BVH)
        if constexpr (kWatertightTriangles<Tests>) {
            if (blas.nodes4 && !stats) {
                auto occludesLeaf = [&](uint32_t first, uint32_t count, float tLimit) {
                    return AnyTriangle(blas.triangles + first, count, setup, tLimit);
                };
                return Traverse4<Query::kOccluded>(blas.nodes4, setup, tMax, occludesLeaf);
            }
        }
        if (blas.nodes4 && !stats)
            return Traverse4<Query::kOccluded>(blas.nodes4, setup, tMax, occludes);
#endif
        return Traverse<Query::kOccluded>(blas.nodes, setup, tMax, occludes, stats);
    }
    const RaySetup setup = MakeBoxRaySetup(objectRay);
    const SphereRay sphereRay = ToObjectSpaceExact(ray, inst);
    return Traverse<Query::kOccluded>(
        blas.nodes, setup, tMax,
        [&](uint32_t slot, float tLimit) {
            float t;
            return Tests::IntersectSphere(blas.spheres[slot], sphereRay, tLimit, &t);
        },
        stats);
}

// Closest hit along ray within (0, ray.tMax].
template <class Tests = PrimitiveTests>
RT_HD inline bool IntersectScene(const TlasView& scene, const Ray& ray, SceneHit* hit,
                                 TraversalStats* stats = nullptr) {
    if (!IsTraceable(ray)) return false;
    const RaySetup setup = MakeBoxRaySetup(ray);
    float tMax = ray.tMax;
    return Traverse<Query::kIntersect>(
        scene.nodes, setup, tMax,
        [&](uint32_t id, float& tBest) {
            const Instance& inst = scene.instances[id];
            const BlasView& blas = scene.blases[inst.blasId];
            if (!IntersectBlas<Tests>(blas, inst, ray, tBest, hit, stats)) return false;
            hit->instance = id;
            return true;
        },
        stats);
}

// Whether anything blocks ray within (0, tMax).
template <class Tests = PrimitiveTests>
RT_HD inline bool OccludedScene(const TlasView& scene, const Ray& ray,
                                TraversalStats* stats = nullptr) {
    if (!IsTraceable(ray)) return false;
    const RaySetup setup = MakeBoxRaySetup(ray);
    float tMax = ray.tMax;
    return Traverse<Query::kOccluded>(
        scene.nodes, setup, tMax,
        [&](uint32_t id, float tLimit) {
            const Instance& inst = scene.instances[id];
            const BlasView& blas = scene.blases[inst.blasId];
            return OccludedBlas<Tests>(blas, inst, ray, tLimit, stats);
        },
        stats);
}

}  // namespace rtrt
