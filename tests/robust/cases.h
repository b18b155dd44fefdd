#pragma once
// The hard cases as plain data, and RT_HD evaluators that turn one case into one result. The CPU
// runner (cpu_runner.h) calls the evaluators in a loop compiled with -ffp-contract=off, the GPU
// runner (gpu_runner.cu) calls the very same functions in a kernel compiled by nvcc with its
// default contraction (--fmad=true), so both back ends are held to the same expected values.
#include "engine/bvh/traversal/scene_traversal.h"
#include "engine/render_rt/shading/optics.h"
#include "engine/render_rt/surface.h"

namespace rtrt::robust {

// --- Primitive-level cases --------------------------------------------------------------------

struct SlabCase {
    vec3 boxMin, boxMax;
    Ray ray;  // ray.tMax bounds the test
};

RT_HD inline uint32_t EvaluateSlab(const SlabCase& c) {
    float tEntry;
    return SlabTest(c.boxMin, c.boxMax, MakeBoxRaySetup(c.ray), c.ray.tMax, &tEntry) ? 1u : 0u;
}

struct SphereCase {
    Sphere sphere;
    Ray ray;
};

struct PrimResult {
    uint32_t hit;
    float t;
};

RT_HD inline PrimResult EvaluateSphere(const SphereCase& c) {
    PrimResult r{0u, 0.0f};
    float t;
    if (IntersectSphere(c.sphere, MakeBoxRaySetup(c.ray), c.ray.tMax, &t)) r = {1u, t};
    return r;
}

struct TriangleCase {
    Triangle triangle;
    Ray ray;
};

RT_HD inline PrimResult EvaluateTriangle(const TriangleCase& c) {
    PrimResult r{0u, 0.0f};
    TriangleHit h;
    if (IntersectTriangle(c.triangle, MakeRaySetup(c.ray), c.ray.tMax, &h)) r = {1u, h.t};
    return r;
}

// --- Scene-level cases: the two-level traversal against brute force ----------------------------

struct SceneResult {
    uint32_t hit;        // IntersectScene (CPU: 4-wide BLAS traversal; GPU: binary)
    uint32_t binaryHit;  // IntersectScene through the binary BVH on both back ends
    uint32_t bruteHit;   // every primitive of every instance tested
    uint32_t occluded;   // OccludedScene with the ray's own tMax: must equal hit
    // With tMax cut to just past the closest hit, any-hit and closest-hit still agree. (Not
    // necessarily a hit: a triangle's t may err by its error bound, 1e-3 relative for grazing
    // rays, while the node box's entry distance is exact to an ulp, so a box can start beyond
    // 1.001 t; both queries then cull it alike.)
    uint32_t occludedNear, hitNear;
    float t, binaryT, bruteT;
    float recheckT;  // the reported primitive tested alone: a tie must be a true tie
    uint32_t instance, prim;
};

// Tests one primitive of an instance's BLAS, as the traversals do; kInfinity when missed.
RT_HD inline float PrimitiveT(const BlasView& blas, uint32_t slot, const Instance& inst,
                              const Ray& ray, float tMax) {
    if (blas.kind == GeometryKind::kTriangles) {
        TriangleHit h;
        return IntersectTriangle(blas.triangles[slot], MakeRaySetup(ToObjectSpace(ray, inst)), tMax,
                                 &h)
                   ? h.t
                   : kInfinity;
    }
    float t;
    return IntersectSphere(blas.spheres[slot], ToObjectSpaceExact(ray, inst), tMax, &t) ? t
                                                                                        : kInfinity;
}

struct SceneEvaluator {
    TlasView scene;
    uint32_t instanceCount;

    RT_HD SceneResult operator()(const Ray& ray) const {
        SceneResult r{};
        r.t = r.binaryT = r.bruteT = r.recheckT = kInfinity;
        SceneHit hit;
        r.hit = IntersectScene(scene, ray, &hit) ? 1u : 0u;
        if (r.hit) {
            r.t = hit.t;
            r.instance = hit.instance;
            r.prim = hit.prim;
            const Instance& inst = scene.instances[hit.instance];
            r.recheckT = PrimitiveT(scene.blases[inst.blasId], hit.prim, inst, ray, ray.tMax);
        }
        TraversalStats stats;  // asking for stats selects the binary BVH on the CPU too
        SceneHit binary;
        r.binaryHit = IntersectScene(scene, ray, &binary, &stats) ? 1u : 0u;
        if (r.binaryHit) r.binaryT = binary.t;
        // Brute force. A ray that is not traceable (NaN, infinite, zero direction) hits nothing
        // by definition, the same gate IntersectScene applies.
        if (IsTraceable(ray)) {
            for (uint32_t i = 0; i < instanceCount; ++i) {
                const Instance& inst = scene.instances[i];
                const BlasView& blas = scene.blases[inst.blasId];
                for (uint32_t slot = 0; slot < blas.primCount; ++slot) {
                    const float tMax = r.bruteHit ? r.bruteT : ray.tMax;
                    const float t = PrimitiveT(blas, slot, inst, ray, tMax);
                    if (t < tMax) {
                        r.bruteHit = 1u;
                        r.bruteT = t;
                    }
                }
            }
        }
        r.occluded = OccludedScene(scene, ray) ? 1u : 0u;
        Ray near = ray;
        if (r.hit) near.tMax = r.t * 1.001f;
        r.occludedNear = OccludedScene(scene, near) ? 1u : 0u;
        SceneHit nearHit;
        r.hitNear = IntersectScene(scene, near, &nearHit) ? 1u : 0u;
        return r;
    }
};

// --- Spawned secondary rays: leave the surface, never re-hit it -------------------------------

enum class SpawnMode : uint32_t {
    kReflect = 0,  // the mirror direction about the geometric normal (outward)
    kGiven = 1,    // dir as given (a light direction, a refracted direction...)
};

struct SpawnCase {
    Ray primary;
    vec3 dir;
    SpawnMode mode;
};

struct SpawnResult {
    uint32_t primaryHit;
    uint32_t primaryInstance;
    uint32_t spawnedHit;  // closest hit of the spawned ray
    uint32_t spawnedInstance;
    uint32_t occluded;  // any hit of the spawned ray (a shadow ray toward an infinitely far light)
    float spawnedT;     // in units of the spawned direction, which is unit length
    vec3 point;         // the primary hit point
};

struct SpawnEvaluator {
    TlasView scene;

    RT_HD SpawnResult operator()(const SpawnCase& c) const {
        SpawnResult r{};
        r.spawnedT = kInfinity;
        SceneHit hit;
        if (!IntersectScene(scene, c.primary, &hit)) return r;
        r.primaryHit = 1u;
        r.primaryInstance = hit.instance;
        RenderSceneView view{};
        view.tlas = scene;
        const Surface s = MakeSurface(view, c.primary, hit);
        r.point = s.point;
        const vec3 dir = c.mode == SpawnMode::kReflect
                             ? Reflect(-glm::normalize(c.primary.dir), s.geomNormal)
                             : glm::normalize(c.dir);
        const Ray spawned = SpawnRay(s, dir);
        SceneHit next;
        if (IntersectScene(scene, spawned, &next)) {
            r.spawnedHit = 1u;
            r.spawnedInstance = next.instance;
            r.spawnedT = next.t;
        }
        r.occluded = OccludedScene(scene, spawned) ? 1u : 0u;
        return r;
    }
};

}  // namespace rtrt::robust
