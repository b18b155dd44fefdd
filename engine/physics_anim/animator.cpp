#include "engine/physics_anim/animator.h"

namespace rtrt::physics {

LocalTransform EvaluateAnimator(const Animator& animator) {
    LocalTransform pose = animator.base;
    if (animator.clip) SampleClip(*animator.clip, animator.time, pose);
    for (const ProceduralMotion& motion : animator.motions)
        ApplyMotion(motion, animator.time, pose);
    return pose;
}

uint32_t AnimateEntities(ecs::Registry& registry, float dt) {
    uint32_t posed = 0;
    registry.View<Animator, LocalTransform>().Each(
        [&](ecs::Entity e, Animator& animator, LocalTransform& local) {
            if (!animator.playing) return;
            animator.time += static_cast<double>(animator.speed) * dt;
            local = EvaluateAnimator(animator);
            registry.MarkChanged<LocalTransform>(e);
            ++posed;
        });
    return posed;
}

void AddAnimationSystem(ecs::Scheduler& scheduler) {
    scheduler.AddSystem("animation", "animators",
                        [](ecs::Registry& registry, float dt) { AnimateEntities(registry, dt); });
}

}  // namespace rtrt::physics
