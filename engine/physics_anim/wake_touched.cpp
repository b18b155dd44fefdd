// PhysicsWorld::WakeTouched: sleepers woken by what moved near them before a step.
#include "engine/core/parallel_compact.h"
#include "engine/physics_anim/physics_world.h"

namespace rtrt::physics {

void PhysicsWorld::WakeTouched() {
    // A sleeper near a body that moved during the last step wakes; one it wakes counts as moving,
    // so a disturbance spreads through a resting pile (within this pass, or over the next steps).
    // The pass is serial (its order matters) and reads only the dense motion flags, which stay in
    // the core's cache where the bodies would not.
    constexpr uint8_t kSleeperMask = kDynamic | kAwake;
    const auto isSleeper = [&](uint32_t body) {
        return (motion_[body] & kSleeperMask) == kDynamic;
    };
    auto wake = [&](uint32_t sleeper, uint32_t other) {
        const uint8_t o = motion_[other];
        const bool moved = (o & (kAwake | kResting)) == kAwake || (o & kFresh) != 0;
        if (!isSleeper(sleeper) || !moved) return;
        motion_[sleeper] = kDynamic | kAwake;
        SimBody& body = bodies_[sleeper];
        body.awake = true;
        body.restingTime = 0.0f;
        body.invInertiaWorld = WorldInverseInertia(body.rotation, body.invInertiaLocal);
    };
    // Only a pair that holds a sleeper when the pass begins can wake anything (the pass never
    // puts a body to sleep), so those are found first, in parallel, and the serial pass visits
    // them alone in the same order: where most bodies are awake it has little left to do.
    sleeperPairs_.resize(pairs_.size());
    sleeperPairs_.resize(ParallelCompact(
        pairs_.size(), chunkStarts_,
        [&](size_t k) { return isSleeper(pairs_[k].first) || isSleeper(pairs_[k].second); },
        [&](size_t k, uint32_t out) { sleeperPairs_[out] = static_cast<uint32_t>(k); }));
    for (const uint32_t k : sleeperPairs_) {
        const auto [a, b] = pairs_[k];
        wake(a, b);
        wake(b, a);
    }
    // Planes are outside the broad phase: one just placed or moved wakes the sleepers within
    // reach of its half-space, where it is or was (rare, so a pass over the bodies is enough).
    for (const uint32_t plane : planes_) {
        if ((motion_[plane] & kFresh) == 0) continue;
        const SimBody& p = bodies_[plane];
        const vec3 normal = glm::normalize(p.orientation * p.collider.normal);
        const vec3 normalWas = glm::normalize(p.previousOrientation * p.collider.normal);
        for (uint32_t i = 0; i < bodies_.size(); ++i) {
            if (!isSleeper(i) || !bodies_[i].hasCollider) continue;
            const float reach = bodies_[i].boundingRadius + settings_.contactMargin;
            if (glm::dot(normal, bodies_[i].position - p.position) < reach ||
                glm::dot(normalWas, bodies_[i].position - p.previousPosition) < reach)
                wake(i, plane);
        }
    }
}

}  // namespace rtrt::physics
