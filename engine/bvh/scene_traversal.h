#pragma once
// Two-level traversal: the TLAS over instances, then each reached instance's BLAS in object
// space. Object-space directions are not renormalised, so t means the same in both spaces.
#include "engine/bvh/blas.h"
#include "engine/bvh/instance.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/bvh/traversal.h"
#include "engine/bvh/triangle_intersect.h"

// The CPU back end traverses triangle BLASes through their 4-wide collapse (SSE); the GPU and the
// heatmap's node counts use the binary BVH.
#if !defined(__CUDACC__)
#include "engine/bvh/bvh4_traversal.h"
#define RTRT_HOST_WIDE_BVH 1
#endif

namespace rtrt {

struct TlasView {
    const BvhNode* nodes;
    const uint32_t* instanceOrder;  // leaf slot -> instance index
    const Instance* instances;
    const BlasView* blases;
};

struct SceneHit {
    float t;
    uint32_t instance;
    uint32_t prim;  // leaf slot in the instance's BLAS
    float b1, b2;   // triangle barycentrics
};

RT_HD inline Ray ToObjectSpace(const Ray& ray, const Instance& inst) {
    Ray r;
    // worldToObject.Point(o) = L^-1 (o - c) with c the instance's world position, computed in
    // that order: o - c is exact for an origin near its instance (Sterbenz), where the product
    // form L^-1 o - L^-1 c cancels two numbers of size |c| and errs by an ulp of |c|. Far from
    // the world origin that error (1e-3 at 1e4) moved shadow rays spawned near a corner of a
    // closed room onto the neighbouring wall, and light leaked in (tests/robust, closed room).
    const vec3 position(inst.objectToWorld.row[0].w, inst.objectToWorld.row[1].w,
                        inst.objectToWorld.row[2].w);
    r.origin = inst.worldToObject.Vector(ray.origin - position);
    r.dir = inst.worldToObject.Vector(ray.dir);
    r.tMax = ray.tMax;
    r.pad = 0.0f;
    return r;
}

RT_HD inline bool IntersectBlas(const BlasView& blas, const Ray& objectRay, float& tMax,
                                SceneHit* hit, TraversalStats* stats) {
    if (blas.kind == GeometryKind::kTriangles) {
        const RaySetup setup = MakeRaySetup(objectRay);
        auto intersect = [&](uint32_t slot, float& tBest) {
            TriangleHit h;
            if (!IntersectTriangle(blas.triangles[slot], setup, tBest, &h)) return false;
            tBest = h.t;
            hit->t = h.t;
            hit->prim = slot;
            hit->b1 = h.b1;
            hit->b2 = h.b2;
            return true;
        };
#if defined(RTRT_HOST_WIDE_BVH)
        if (blas.nodes4 && !stats) return TraverseClosest4(blas.nodes4, setup, tMax, intersect);
#endif
        return TraverseClosest(blas.nodes, setup, tMax, intersect, stats);
    }
    const RaySetup setup = MakeBoxRaySetup(objectRay);
    return TraverseClosest(
        blas.nodes, setup, tMax,
        [&](uint32_t slot, float& tBest) {
            float t;
            if (!IntersectSphere(blas.spheres[slot], setup, tBest, &t)) return false;
            tBest = t;
            hit->t = t;
            hit->prim = slot;
            hit->b1 = hit->b2 = 0.0f;
            return true;
        },
        stats);
}

RT_HD inline bool OccludedBlas(const BlasView& blas, const Ray& objectRay, float tMax,
                               TraversalStats* stats) {
    if (blas.kind == GeometryKind::kTriangles) {
        const RaySetup setup = MakeRaySetup(objectRay);
        auto occludes = [&](uint32_t slot, float tLimit) {
            TriangleHit h;
            return IntersectTriangle(blas.triangles[slot], setup, tLimit, &h);
        };
#if defined(RTRT_HOST_WIDE_BVH)
        if (blas.nodes4 && !stats) return TraverseAny4(blas.nodes4, setup, tMax, occludes);
#endif
        return TraverseAny(blas.nodes, setup, tMax, occludes, stats);
    }
    const RaySetup setup = MakeBoxRaySetup(objectRay);
    return TraverseAny(
        blas.nodes, setup, tMax,
        [&](uint32_t slot, float tLimit) {
            float t;
            return IntersectSphere(blas.spheres[slot], setup, tLimit, &t);
        },
        stats);
}

// Closest hit along ray within (0, ray.tMax].
RT_HD inline bool IntersectScene(const TlasView& scene, const Ray& ray, SceneHit* hit,
                                 TraversalStats* stats = nullptr) {
    if (!IsTraceable(ray)) return false;
    const RaySetup setup = MakeBoxRaySetup(ray);
    float tMax = ray.tMax;
    return TraverseClosest(
        scene.nodes, setup, tMax,
        [&](uint32_t slot, float& tBest) {
            const uint32_t id = scene.instanceOrder[slot];
            const Instance& inst = scene.instances[id];
            if (!IntersectBlas(scene.blases[inst.blasId], ToObjectSpace(ray, inst), tBest, hit,
                               stats))
                return false;
            hit->instance = id;
            return true;
        },
        stats);
}

// Whether anything blocks ray within (0, tMax).
RT_HD inline bool OccludedScene(const TlasView& scene, const Ray& ray,
                                TraversalStats* stats = nullptr) {
    if (!IsTraceable(ray)) return false;
    const RaySetup setup = MakeBoxRaySetup(ray);
    return TraverseAny(
        scene.nodes, setup, ray.tMax,
        [&](uint32_t slot, float tLimit) {
            const Instance& inst = scene.instances[scene.instanceOrder[slot]];
            Ray objectRay = ToObjectSpace(ray, inst);
            return OccludedBlas(scene.blases[inst.blasId], objectRay, tLimit, stats);
        },
        stats);
}

}  // namespace rtrt
