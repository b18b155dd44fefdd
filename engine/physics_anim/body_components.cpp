// PhysicsWorld::Gather and WriteBack: the world's bodies read from the registry's components
// before a frame's steps, and written back to them after.
#include "engine/core/parallel_compact.h"
#include "engine/core/parallel_for.h"
#include "engine/physics_anim/physics_world.h"
#include "engine/physics_anim/quat_interp.h"

namespace rtrt::physics {

using ecs::Entity;
using ecs::Registry;

namespace {

// Work per TBB task: a body's components are a few cache lines.
constexpr size_t kBodyGrain = 1024;

// Where a body goes in the step's lists (Gather's).
enum BodyPlace : uint8_t { kBroadPhase, kOutside, kPlane };

}  // namespace

void PhysicsWorld::Gather(Registry& registry, bool stepFollows) {
    // The view is walked once for the components' places, and the bodies are filled from them in
    // parallel: each reads and writes only its own components, and a serial pass would pull
    // every body's cache lines from the cores that stepped it. The bodies are reset there too:
    // a serial reset of 10,000 bodies costs more than the walk. The first step's StartStep is done
    // there too, and each body's place in the lists is noted in a byte, so that the serial pass
    // that builds them reads 1 byte per body instead of a cache line of another core's.
    components_.clear();
    registry.View<RigidBody, LocalTransform>().Each(
        [&](Entity e, RigidBody& rb, LocalTransform& local) {
            components_.push_back({e, &rb, &local});
        });
    bodies_.resize(components_.size());
    motion_.resize(bodies_.size());
    places_.resize(bodies_.size());
    ParallelFor(0, bodies_.size(), kBodyGrain, bodyAffinity_, [&](size_t i) {
        SimBody& s = bodies_[i];
        const auto [e, body, transform] = components_[i];
        s = SimBody{};
        s.entity = e;
        s.body = body;
        s.local = transform;
        RigidBody& rb = *body;
        LocalTransform& local = *transform;
        if (const Collider* collider = registry.Get<Collider>(e)) {
            s.hasCollider = true;
            s.collider = *collider;
        }
        const bool isPlane = s.hasCollider && s.collider.shape == ColliderShape::kPlane;
        s.dynamic = rb.mass > 0.0f && !isPlane;
        s.restitution = rb.restitution;
        s.friction = rb.friction;
        s.rollingResistance = rb.rollingResistance;
        s.boundingRadius = s.hasCollider ? BoundingRadius(s.collider) : 0.0f;
        if (s.dynamic) {
            if (!rb.state.initialized) {
                Teleport(rb, local.translation, glm::normalize(local.rotation));
            }
            // Sleeping zeroes the velocities, so a non-zero one was set by the user.
            if (rb.state.sleeping &&
                (rb.velocity != vec3(0.0f) || rb.angularVelocity != vec3(0.0f))) {
                WakeUp(rb);
            }
            s.awake = !rb.state.sleeping;
            s.position = rb.state.position;
            s.orientation = rb.state.orientation;
            s.previousPosition = rb.state.previousPosition;
            s.previousOrientation = rb.state.previousOrientation;
            s.velocity = rb.velocity;
            s.angularVelocity = rb.angularVelocity;
            s.restingTime = rb.state.restingTime;
            s.invMass = 1.0f / rb.mass;
            const vec3 inertia = s.hasCollider ? InertiaDiagonal(s.collider, rb.mass) : vec3(0.0f);
            if (!rb.fixedRotation && inertia.x > 0.0f && inertia.y > 0.0f && inertia.z > 0.0f) {
                s.invInertiaLocal = 1.0f / inertia;
            }
        } else {
            // A static body placed among sleepers (spawned later, or moved by an edit) must wake
            // them, or they would stay inside it: one that no step has seen where it is now
            // counts as having moved.
            s.fresh = !rb.state.initialized || rb.state.position != local.translation ||
                      rb.state.orientation != local.rotation;
            s.position = local.translation;
            s.orientation = glm::normalize(local.rotation);
            // One moved away from sleepers must wake them too, or they would float where it was:
            // its first step's broad phase spans both places (StartStep keeps the old one).
            const bool moved = s.fresh && rb.state.initialized;
            s.previousPosition = moved ? rb.state.position : s.position;
            s.previousOrientation = moved ? glm::normalize(rb.state.orientation) : s.orientation;
            if (stepFollows) {
                rb.state.initialized = true;
                rb.state.position = local.translation;
                rb.state.orientation = local.rotation;
            }
        }
        places_[i] = isPlane ? kPlane : s.hasCollider ? kBroadPhase : kOutside;
        if (stepFollows) StartStep(i);
    });
    // The frame's steps share these lists: the colliders do not change between them.
    planes_.clear();
    broadBodies_.clear();
    outsideBodies_.clear();
    for (uint32_t i = 0; i < bodies_.size(); ++i) {
        if (places_[i] == kPlane) planes_.push_back(i);
        (places_[i] == kBroadPhase ? broadBodies_ : outsideBodies_).push_back(i);
    }
}

void PhysicsWorld::WriteBack(Registry& registry, float alpha) {
    // In parallel, each body to its own components; then the moved transforms are marked, in body
    // order, by the registry's bulk MarkChanged (also parallel).
    moved_.assign(bodies_.size(), 0);
    ParallelFor(0, bodies_.size(), kBodyGrain, bodyAffinity_, [&](size_t i) {
        const SimBody& s = bodies_[i];
        if (!s.dynamic) return;
        RigidBody& rb = *s.body;
        rb.velocity = s.velocity;
        rb.angularVelocity = s.angularVelocity;
        rb.state.position = s.position;
        rb.state.orientation = s.orientation;
        rb.state.previousPosition = s.previousPosition;
        rb.state.previousOrientation = s.previousOrientation;
        rb.state.restingTime = s.restingTime;
        rb.state.sleeping = !s.awake;

        vec3 translation = s.position;
        glm::quat rotation = s.orientation;
        if (alpha < 1.0f) {
            translation = glm::mix(s.previousPosition, s.position, alpha);
            rotation = Slerp(s.previousOrientation, s.orientation, alpha);
        }
        LocalTransform& local = *s.local;
        if (local.translation == translation && local.rotation == rotation) return;
        local.translation = translation;
        local.rotation = rotation;
        moved_[i] = 1;
    });
    movedEntities_.resize(bodies_.size());
    movedEntities_.resize(ParallelCompact(
        bodies_.size(), chunkStarts_, [&](size_t i) { return moved_[i] != 0; },
        [&](size_t i, uint32_t at) { movedEntities_[at] = bodies_[i].entity; }));
    registry.MarkChanged<LocalTransform>(std::span<const ecs::Entity>(movedEntities_));
}

}  // namespace rtrt::physics
