#pragma once
// Both levels of the scene in one traversal loop, one stack. Nested loops (a TLAS loop whose leaf
// runs a whole BLAS loop) leave a GPU warp's lanes idle whenever some lanes are in a BLAS and
// others still in the TLAS: a warp executes the union of both loops. Here every iteration does
// the same work, a node pair or a leaf, whichever level each lane is in.
//
// Entering an instance pushes a return-to-world marker and continues with the BLAS's root in
// object space; popping the marker restores the world-space ray. TLAS leaves with several
// instances push the later ones as instance entries, last first, so they are visited in order.
// The visiting order, the hits and the heatmap's counts are those of the nested form
// (scene_traversal.h), which tests check.
#include "engine/bvh/blas.h"
#include "engine/bvh/instance.h"
#include "engine/bvh/sphere_intersect.h"
#include "engine/bvh/traversal.h"
#include "engine/bvh/triangle_intersect.h"

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
    r.origin = inst.worldToObject.Point(ray.origin);
    r.dir = inst.worldToObject.Vector(ray.dir);
    r.tMax = ray.tMax;
    r.pad = 0.0f;
    return r;
}

// A TLAS pending pair or a BLAS pending pair is a node index; these two kinds of entry are not.
inline constexpr uint32_t kReturnToWorld = 0xffffffffu;
inline constexpr uint32_t kInstanceEntry = 0x80000000u;  // | TLAS leaf slot
// One TLAS path, a leaf's waiting instances and one BLAS path.
inline constexpr uint32_t kTwoLevelStackSize = 2 * kBvhStackSize + 8;

// Closest hit (kAnyHit false: hit records it, tMax shrinks to it) or any hit before tMax.
template <bool kAnyHit>
RT_HD inline bool TraverseTwoLevel(const TlasView& scene, const Ray& ray, float& tMax,
                                   SceneHit* hit, TraversalStats* stats) {
    if (!IsTraceable(ray)) return false;
    const RaySetup world = MakeBoxRaySetup(ray);
    RaySetup setup = world;
    const BvhNode* nodes = scene.nodes;
    const BlasView* blas = nullptr;  // null while in the TLAS
    uint32_t instanceId = 0;
    uint32_t stack[kTwoLevelStackSize];
    uint32_t stackSize = 0;
    bool found = false;

    // Switches to the instance at a TLAS leaf slot if the ray meets its BLAS's root box.
    auto enterInstance = [&](uint32_t slot) {
        const uint32_t id = scene.instanceOrder[slot];
        const Instance& inst = scene.instances[id];
        const BlasView& target = scene.blases[inst.blasId];
        const Ray objectRay = ToObjectSpace(ray, inst);
        const RaySetup objectSetup = target.kind == GeometryKind::kTriangles
                                         ? MakeRaySetup(objectRay)
                                         : MakeBoxRaySetup(objectRay);
        if (stats) {
            ++stats->primsTested;
            ++stats->nodesVisited;
        }
        float tRoot;
        if (!SlabTest(target.nodes[0], objectSetup, tMax, &tRoot)) return false;
        stack[stackSize++] = kReturnToWorld;
        setup = objectSetup;
        nodes = target.nodes;
        blas = &target;
        instanceId = id;
        return true;
    };

    float tRoot;
    if (stats) ++stats->nodesVisited;
    if (!SlabTest(nodes[0], setup, tMax, &tRoot)) return false;
    uint32_t current = 0;
    for (;;) {
        const BvhNode& node = nodes[current];
        bool descended = false;
        if (!node.IsLeaf()) {
            const uint32_t left = node.leftFirst;
            float tLeft, tRight;
            const bool hitLeft = SlabTest(nodes[left], setup, tMax, &tLeft);
            const bool hitRight = SlabTest(nodes[left + 1], setup, tMax, &tRight);
            if (stats) stats->nodesVisited += 2;
            if (hitLeft && hitRight) {
                // Closest hit visits the nearer child first; any hit keeps the builder's order.
                const bool leftFirst = kAnyHit || tLeft <= tRight;
                stack[stackSize++] = leftFirst ? left + 1 : left;
                current = leftFirst ? left : left + 1;
                descended = true;
            } else if (hitLeft || hitRight) {
                current = hitLeft ? left : left + 1;
                descended = true;
            }
        } else if (blas == nullptr) {
            for (uint32_t i = node.primCount - 1; i >= 1; --i)
                stack[stackSize++] = kInstanceEntry | (node.leftFirst + i);
            if (enterInstance(node.leftFirst)) {
                current = 0;
                descended = true;
            }
        } else {
            for (uint32_t i = 0; i < node.primCount; ++i) {
                const uint32_t slot = node.leftFirst + i;
                if (stats) ++stats->primsTested;
                float t;
                if (blas->kind == GeometryKind::kTriangles) {
                    TriangleHit h;
                    if (!IntersectTriangle(blas->triangles[slot], setup, tMax, &h)) continue;
                    if constexpr (kAnyHit) return true;
                    t = h.t;
                    hit->b1 = h.b1;
                    hit->b2 = h.b2;
                } else {
                    if (!IntersectSphere(blas->spheres[slot], setup, tMax, &t)) continue;
                    if constexpr (kAnyHit) return true;
                    hit->b1 = hit->b2 = 0.0f;
                }
                tMax = t;
                hit->t = t;
                hit->prim = slot;
                hit->instance = instanceId;
                found = true;
            }
        }
        if (descended) continue;
        // Pop until there is a node to visit: markers switch back to the world, instance entries
        // enter their instance.
        for (;;) {
            if (stackSize == 0) return found;
            const uint32_t entry = stack[--stackSize];
            if (entry == kReturnToWorld) {
                setup = world;
                nodes = scene.nodes;
                blas = nullptr;
            } else if ((entry & kInstanceEntry) != 0 && blas == nullptr) {
                if (enterInstance(entry & ~kInstanceEntry)) {
                    current = 0;
                    break;
                }
            } else {
                current = entry;
                break;
            }
        }
    }
}

}  // namespace rtrt
