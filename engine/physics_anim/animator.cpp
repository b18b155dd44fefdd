#include "engine/physics_anim/animator.h"

#include <cstdint>
#include <vector>

#include "engine/core/parallel_for.h"

namespace rtrt::physics {

namespace {

LocalTransform Animated(const Animator& animator) {
    LocalTransform pose = animator.base;
    if (animator.clip) {
        SampleClip(*animator.clip, animator.time, pose);
        if (!animator.clip->translation.times.empty()) pose.translation += animator.keyOffset;
    }
    for (const ProceduralMotion& motion : animator.motions)
        ApplyMotion(motion, animator.time, pose);
    return pose;
}

bool SamePose(const LocalTransform& a, const LocalTransform& b) {
    return a.translation == b.translation && a.rotation == b.rotation && a.scale == b.scale;
}

}  // namespace

LocalTransform EvaluateAnimator(const Animator& animator) {
    LocalTransform pose = Animated(animator);
    if (animator.moved != vec3(0.0f)) pose.translation += animator.moved;
    if (animator.turned != glm::identity<glm::quat>())
        pose.rotation = animator.turned * pose.rotation;
    return pose;
}

void PlaceAnimated(Animator& animator, vec3 position, glm::quat rotation) {
    const LocalTransform animated = Animated(animator);
    animator.moved = position - animated.translation;
    animator.turned = glm::normalize(rotation * glm::inverse(animated.rotation));
}

uint32_t AnimateEntities(ecs::Registry& registry, float dt) {
    struct Posed {
        ecs::Entity entity;
        Animator* animator;
        LocalTransform* local;
    };
    // The poses are independent: sampled in parallel, then marked in the view's order here.
    std::vector<Posed> posed;
    registry.View<Animator, LocalTransform>().Each(
        [&](ecs::Entity e, Animator& animator, LocalTransform& local) {
            if (animator.playing) posed.push_back({e, &animator, &local});
        });
    std::vector<uint8_t> moved(posed.size(), 0);
    ParallelFor(0, posed.size(), 64, [&](size_t i) {
        Animator& animator = *posed[i].animator;
        animator.time += static_cast<double>(animator.speed) * dt;
        const LocalTransform pose = EvaluateAnimator(animator);
        moved[i] = !SamePose(pose, *posed[i].local);
        *posed[i].local = pose;
    });
    for (size_t i = 0; i < posed.size(); ++i)
        if (moved[i]) registry.MarkChanged<LocalTransform>(posed[i].entity);
    return uint32_t(posed.size());
}

void AddAnimationSystem(ecs::Scheduler& scheduler) {
    scheduler.AddSystem("animation", "animators",
                        [](ecs::Registry& registry, float dt) { AnimateEntities(registry, dt); });
}

}  // namespace rtrt::physics
