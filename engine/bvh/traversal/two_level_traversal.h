#pragma once
// Both levels of the scene in one traversal loop, one stack. Nested loops (a TLAS loop whose leaf
// runs a whole BLAS loop) leave a GPU warp's lanes idle whenever some lanes are in a BLAS and
// others still in the TLAS: a warp executes the union of both loops. Here every iteration does
// the same work, a node pair or a leaf, whichever level each lane is in.
//
// Entering an instance pushes a return-to-world marker and continues with the BLAS's root in
// object space; popping the marker restores the world-space ray. TLAS leaves with several
// instances (which no builder of the engine makes, tlas.h, but which the loop supports as BLAS
// leaves are supported) push the later ones as instance entries, last first, so they are visited
// in order.
// The visiting order, the hits and the heatmap's counts are those of the nested form
// (scene_traversal.h), which tests check.
#include "engine/bvh/blas/blas.h"
#include "engine/bvh/tlas/instance.h"
#include "engine/bvh/traversal/traversal.h"
#include "engine/geometry/primitive_tests.h"

namespace rtrt {

struct TlasView {
    const BvhNode* nodes;  // leaves name their instances (tlas.h)
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
    r.origin = inst.VectorToObject(ray.origin - inst.Position());
    r.dir = inst.VectorToObject(ray.dir);
    r.tMax = ray.tMax;
    r.pad = 0.0f;
    return r;
}

// The same with the origin in double, for the sphere test (sphere_intersect.h): the float
// transform's entries taken as exact, so that a huge sphere's space keeps the ray's position to
// far below its own float spacing. Evaluated only for sphere BLASes.
RT_HD inline SphereRay ToObjectSpaceExact(const Ray& ray, const Instance& inst) {
    const glm::dvec3 local = glm::dvec3(ray.origin) - glm::dvec3(inst.Position());
    SphereRay r;
    for (int i = 0; i < 3; ++i) r.origin[i] = glm::dot(glm::dvec3(inst.InverseRow(i)), local);
    r.dir = inst.VectorToObject(ray.dir);
    return r;
}

// Stack entries: a node index of the level in use, or one of these two.
inline constexpr uint32_t kReturnToWorld = 0xffffffffu;
inline constexpr uint32_t kInstanceEntry = 0x80000000u;  // | instance index
inline constexpr uint32_t kNoNode = 0xfffffffeu;
// One TLAS path, a leaf's waiting instances and one BLAS path.
inline constexpr uint32_t kTwoLevelStackSize = 2 * kBvhStackSize + 8;

// Whether pred holds for any active lane of the warp; on the CPU, one lane.
RT_HD inline bool AnyLane(bool pred) {
#if defined(__CUDA_ARCH__)
    return __any_sync(__activemask(), pred);
#else
    return pred;
#endif
}

// Either query (traversal.h): kIntersect records the closest hit in hit and shrinks tMax to it;
// kOccluded returns at the first primitive before tMax. Tests supplies the primitive tests
// (primitive_tests.h).
//
// The loop has the while-while form of Aila and Laine (2009): lanes step through interior nodes
// together and set a leaf aside when they reach one; on the GPU they keep descending until every
// lane of the warp holds a leaf ("speculative traversal"), and then the leaves are intersected
// together. A lane alone (the CPU) intersects each leaf as soon as it is found, which gives the
// nested form's order exactly.
template <Query kQuery, class Tests = PrimitiveTests>
RT_HD inline bool TraverseTwoLevel(const TlasView& scene, const Ray& ray, float& tMax,
                                   SceneHit* hit, TraversalStats* stats) {
    if (!IsTraceable(ray)) return false;
    // The world-space setup is recomputed on the way back from an instance rather than kept:
    // registers, not the three divisions, limit how many rays a GPU keeps in flight.
    RaySetup setup = MakeBoxRaySetup(ray);
    const BvhNode* nodes = scene.nodes;
    const BlasView* blas = nullptr;  // null while in the TLAS
    bool triangles = false;          // the BLAS in use holds triangles (else spheres)
    uint32_t instanceId = 0;
    uint32_t stack[kTwoLevelStackSize];
    uint32_t stackSize = 0;
    bool found = false;

    // Switches to instance id if the ray meets its BLAS's root box.
    auto enterInstance = [&](uint32_t id) {
        const Instance& inst = scene.instances[id];
        const BlasView& target = scene.blases[inst.blasId];
        const Ray objectRay = ToObjectSpace(ray, inst);
        const bool isTriangles = target.kind == GeometryKind::kTriangles;
        const RaySetup objectSetup =
            isTriangles ? MakeRaySetup(objectRay) : MakeBoxRaySetup(objectRay);
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
        triangles = isTriangles;
        instanceId = id;
        return true;
    };
    // The next pending node of the level in use, or kNoNode when the stack is empty or its top
    // leaves the level (a marker or an instance entry: handled once no leaf is set aside).
    auto popNode = [&]() {
        if (stackSize == 0) return kNoNode;
        const uint32_t top = stack[stackSize - 1];
        if (top == kReturnToWorld || (blas == nullptr && (top & kInstanceEntry) != 0))
            return kNoNode;
        --stackSize;
        return top;
    };

    float tRoot;
    if (stats) ++stats->nodesVisited;
    if (!SlabTest(nodes[0], setup, tMax, &tRoot)) return false;
    uint32_t current = 0;
    uint32_t postponed = kNoNode;  // a leaf set aside, of the level in use
    for (;;) {
        // Interior nodes, until this lane (and on the GPU every lane) holds a leaf.
        while (current != kNoNode) {
            const BvhNode& node = nodes[current];
            if (node.IsLeaf()) {
                if (postponed != kNoNode) break;  // intersect the one set aside first
                postponed = current;
                current = popNode();
            } else {
                const uint32_t left = node.leftFirst;
                float tLeft, tRight;
                const bool hitLeft = SlabTest(nodes[left], setup, tMax, &tLeft);
                const bool hitRight = SlabTest(nodes[left + 1], setup, tMax, &tRight);
                if (stats) stats->nodesVisited += 2;
                if (hitLeft && hitRight) {
                    // kIntersect visits the nearer child first; kOccluded the builder's order.
                    const bool leftFirst = kQuery == Query::kOccluded || tLeft <= tRight;
                    stack[stackSize++] = leftFirst ? left + 1 : left;
                    current = leftFirst ? left : left + 1;
                } else if (hitLeft || hitRight) {
                    current = hitLeft ? left : left + 1;
                } else {
                    current = popNode();
                }
            }
            if (!AnyLane(postponed == kNoNode)) break;
        }
        if (postponed != kNoNode) {
            const BvhNode& leaf = nodes[postponed];
            postponed = kNoNode;
            if (blas == nullptr) {
                // An instance leaf: what was pending at this level waits below the instances.
                if (current != kNoNode) stack[stackSize++] = current;
                current = kNoNode;
                for (uint32_t i = leaf.primCount - 1; i >= 1; --i)
                    stack[stackSize++] = kInstanceEntry | (leaf.leftFirst + i);
                if (enterInstance(leaf.leftFirst)) current = 0;
                continue;
            }
            for (uint32_t i = 0; i < leaf.primCount; ++i) {
                const uint32_t slot = leaf.leftFirst + i;
                if (stats) ++stats->primsTested;
                float t;
                if (triangles) {
                    TriangleHit h;
                    if (!Tests::IntersectTriangle(blas->triangles[slot], setup, tMax, &h)) continue;
                    if constexpr (kQuery == Query::kOccluded) return true;
                    t = h.t;
                    hit->b1 = h.b1;
                    hit->b2 = h.b2;
                } else {
                    const SphereRay exact = ToObjectSpaceExact(ray, scene.instances[instanceId]);
                    if (!Tests::IntersectSphere(blas->spheres[slot], exact, tMax, &t)) continue;
                    if constexpr (kQuery == Query::kOccluded) return true;
                    hit->b1 = hit->b2 = 0.0f;
                }
                tMax = t;
                hit->t = t;
                hit->prim = slot;
                hit->instance = instanceId;
                found = true;
            }
            continue;
        }
        // Nothing in hand: leave the instance at a marker, enter the next waiting instance.
        if (current == kNoNode) {
            if (stackSize == 0) return found;
            const uint32_t entry = stack[--stackSize];
            if (entry == kReturnToWorld) {
                setup = MakeBoxRaySetup(ray);
                nodes = scene.nodes;
                blas = nullptr;
            } else if (blas == nullptr && (entry & kInstanceEntry) != 0) {
                if (enterInstance(entry & ~kInstanceEntry)) current = 0;
            } else {
                current = entry;
            }
        }
    }
}

}  // namespace rtrt
