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
#include "engine/bvh/blas/blas.h"
#include "engine/bvh/tlas/instance.h"
#include "engine/bvh/traversal/traversal.h"
#include "engine/geometry/primitive_tests.h"

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

// The same with the origin in double, for the sphere test (sphere_intersect.h): the float
// transform's entries taken as exact, so that a huge sphere's space keeps the ray's position to
// far below its own float spacing. Evaluated only for sphere BLASes.
RT_HD inline SphereRay ToObjectSpaceExact(const Ray& ray, const Instance& inst) {
    const Affine& m = inst.worldToObject;
    const glm::dvec3 local = glm::dvec3(ray.origin) - glm::dvec3(inst.objectToWorld.row[0].w,
                                                                 inst.objectToWorld.row[1].w,
                                                                 inst.objectToWorld.row[2].w);
    SphereRay r;
    for (int i = 0; i < 3; ++i)
        r.origin[i] = glm::dot(glm::dvec3(m.row[i].x, m.row[i].y, m.row[i].z), local);
    r.dir = m.Vector(ray.dir);
    return r;
}

// Stack entries: a node index of the level in use, or one of these two.
inline constexpr uint32_t kReturnToWorld = 0xffffffffu;
inline constexpr uint32_t kInstanceEntry = 0x80000000u;  // | TLAS leaf slot
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
// kOccluded stops at the first primitive before tMax. Tests supplies the primitive tests
// (primitive_tests.h).
//
// The loop has the while-while form of Aila and Laine (2009): lanes step through interior nodes
// together and set a leaf aside when they reach one; on the GPU they keep descending until every
// lane of the warp holds a leaf ("speculative traversal"), and then the leaves are intersected
// together. A lane alone (the CPU) intersects each leaf as soon as it is found, which gives the
// nested form's order exactly.
//
// The walk is resumable: Step runs one round of the loop and says when the traversal is over, so
// that a lane whose ray finished can take up another ray while the rest of its warp goes on
// (the primary-hit kernel, trace_launch.cuh). TraverseTwoLevel runs one ray to its end.
template <Query kQuery, class Tests = PrimitiveTests>
class TwoLevelWalk {
  public:
    // stack: kTwoLevelStackSize entries, the caller's (an array inside the walk kept nvcc from
    // holding the walk's other members in registers).
    RT_HD explicit TwoLevelWalk(uint32_t* stack) : stack_(stack) {}

    // Starts on ray with tMax; false when the traversal is over at once (a ray that cannot be
    // traced, or the TLAS's root missed), with nothing found.
    RT_HD bool Begin(const TlasView& scene, const Ray& ray, float tMax, TraversalStats* stats) {
        found_ = false;
        tMax_ = tMax;
        if (!IsTraceable(ray)) return false;
        // The world-space setup is recomputed on the way back from an instance rather than kept:
        // registers, not the three divisions, limit how many rays a GPU keeps in flight.
        setup_ = MakeBoxRaySetup(ray);
        nodes_ = scene.nodes;
        blas_ = nullptr;
        triangles_ = false;
        instanceId_ = 0;
        stackSize_ = 0;
        postponed_ = kNoNode;
        float tRoot;
        if (stats) ++stats->nodesVisited;
        if (!SlabTest(nodes_[0], setup_, tMax_, &tRoot)) return false;
        current_ = 0;
        return true;
    }

    // One round: interior nodes until this lane (on the GPU every lane) holds a leaf, then that
    // leaf; or, with nothing in hand, leaving an instance or entering the next waiting one. True
    // once the traversal is over: Found says whether it hit (kIntersect: hit holds the closest).
    RT_HD bool Step(const TlasView& scene, const Ray& ray, SceneHit* hit, TraversalStats* stats) {
        // Interior nodes, until this lane (and on the GPU every lane) holds a leaf.
        while (current_ != kNoNode) {
            const BvhNode& node = nodes_[current_];
            if (node.IsLeaf()) {
                if (postponed_ != kNoNode) break;  // intersect the one set aside first
                postponed_ = current_;
                current_ = PopNode();
            } else {
                const uint32_t left = node.leftFirst;
                float tLeft, tRight;
                const bool hitLeft = SlabTest(nodes_[left], setup_, tMax_, &tLeft);
                const bool hitRight = SlabTest(nodes_[left + 1], setup_, tMax_, &tRight);
                if (stats) stats->nodesVisited += 2;
                if (hitLeft && hitRight) {
                    // kIntersect visits the nearer child first; kOccluded the builder's order.
                    const bool leftFirst = kQuery == Query::kOccluded || tLeft <= tRight;
                    stack_[stackSize_++] = leftFirst ? left + 1 : left;
                    current_ = leftFirst ? left : left + 1;
                } else if (hitLeft || hitRight) {
                    current_ = hitLeft ? left : left + 1;
                } else {
                    current_ = PopNode();
                }
            }
            if (!AnyLane(postponed_ == kNoNode)) break;
        }
        if (postponed_ != kNoNode) {
            const BvhNode& leaf = nodes_[postponed_];
            postponed_ = kNoNode;
            if (blas_ == nullptr) {
                // An instance leaf: what was pending at this level waits below the instances.
                if (current_ != kNoNode) stack_[stackSize_++] = current_;
                current_ = kNoNode;
                for (uint32_t i = leaf.primCount - 1; i >= 1; --i)
                    stack_[stackSize_++] = kInstanceEntry | (leaf.leftFirst + i);
                if (EnterInstance(scene, ray, leaf.leftFirst, stats)) current_ = 0;
                return false;
            }
            for (uint32_t i = 0; i < leaf.primCount; ++i) {
                const uint32_t slot = leaf.leftFirst + i;
                if (stats) ++stats->primsTested;
                float t;
                if (triangles_) {
                    TriangleHit h;
                    if (!Tests::IntersectTriangle(blas_->triangles[slot], setup_, tMax_, &h))
                        continue;
                    if constexpr (kQuery == Query::kOccluded) return found_ = true;
                    t = h.t;
                    hit->b1 = h.b1;
                    hit->b2 = h.b2;
                } else {
                    const SphereRay exact = ToObjectSpaceExact(ray, scene.instances[instanceId_]);
                    if (!Tests::IntersectSphere(blas_->spheres[slot], exact, tMax_, &t)) continue;
                    if constexpr (kQuery == Query::kOccluded) return found_ = true;
                    hit->b1 = hit->b2 = 0.0f;
                }
                tMax_ = t;
                hit->t = t;
                hit->prim = slot;
                hit->instance = instanceId_;
                found_ = true;
            }
            return false;
        }
        // Nothing in hand: leave the instance at a marker, enter the next waiting instance.
        if (current_ == kNoNode) {
            if (stackSize_ == 0) return true;
            const uint32_t entry = stack_[--stackSize_];
            if (entry == kReturnToWorld) {
                setup_ = MakeBoxRaySetup(ray);
                nodes_ = scene.nodes;
                blas_ = nullptr;
            } else if (blas_ == nullptr && (entry & kInstanceEntry) != 0) {
                if (EnterInstance(scene, ray, entry & ~kInstanceEntry, stats)) current_ = 0;
            } else {
                current_ = entry;
            }
        }
        return false;
    }

    RT_HD bool Found() const { return found_; }
    RT_HD float TMax() const { return tMax_; }

  private:
    // Switches to the instance at a TLAS leaf slot if the ray meets its BLAS's root box.
    RT_HD bool EnterInstance(const TlasView& scene, const Ray& ray, uint32_t slot,
                             TraversalStats* stats) {
        const uint32_t id = scene.instanceOrder[slot];
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
        if (!SlabTest(target.nodes[0], objectSetup, tMax_, &tRoot)) return false;
        stack_[stackSize_++] = kReturnToWorld;
        setup_ = objectSetup;
        nodes_ = target.nodes;
        blas_ = &target;
        triangles_ = isTriangles;
        instanceId_ = id;
        return true;
    }
    // The next pending node of the level in use, or kNoNode when the stack is empty or its top
    // leaves the level (a marker or an instance entry: handled once no leaf is set aside).
    RT_HD uint32_t PopNode() {
        if (stackSize_ == 0) return kNoNode;
        const uint32_t top = stack_[stackSize_ - 1];
        if (top == kReturnToWorld || (blas_ == nullptr && (top & kInstanceEntry) != 0))
            return kNoNode;
        --stackSize_;
        return top;
    }

    RaySetup setup_;
    const BvhNode* nodes_ = nullptr;
    const BlasView* blas_ = nullptr;  // null while in the TLAS
    bool triangles_ = false;          // the BLAS in use holds triangles (else spheres)
    bool found_ = false;
    uint32_t instanceId_ = 0;
    uint32_t current_ = kNoNode;
    uint32_t postponed_ = kNoNode;  // a leaf set aside, of the level in use
    float tMax_ = 0.0f;
    uint32_t stackSize_ = 0;
    uint32_t* stack_;
};

template <Query kQuery, class Tests = PrimitiveTests>
RT_HD inline bool TraverseTwoLevel(const TlasView& scene, const Ray& ray, float& tMax,
                                   SceneHit* hit, TraversalStats* stats) {
    uint32_t stack[kTwoLevelStackSize];
    TwoLevelWalk<kQuery, Tests> walk(stack);
    if (!walk.Begin(scene, ray, tMax, stats)) return false;
    while (!walk.Step(scene, ray, hit, stats)) {
    }
    tMax = walk.TMax();
    return walk.Found();
}

}  // namespace rtrt
