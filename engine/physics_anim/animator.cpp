#include "engine/physics_anim/animator.h"

#include <vector>

#include "engine/core/parallel_for.h"

namespace rtrt::physics {

LocalTransform EvaluateAnimator(const Animator& animator) {
    LocalTransform pose = animator.base;
    if (animator.clip) {
        SampleClip(*animator.clip, animator.time, pose);
        if (!animator.clip->translation.times.empty()) pose.translation += animator.keyOffset;
    }
    for (const ProceduralMotion& motion : animator.motions)
        ApplyMotion(motion, animator.time, pose);
    return pose;
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
    ParallelFor(0, posed.size(), 64, [&](size_t i) {
        Animator& animator = *posed[i].animator;
        animator.time += static_cast<double>(animator.speed) * dt;
        *posed[i].local = EvaluateAnimator(animator);
    });
    for (const Posed& p : posed) registry.MarkChanged<LocalTransform>(p.entity);
    return uint32_t(posed.size());
}

void AddAnimationSystem(ecs::Scheduler& scheduler) {
    scheduler.AddSystem("animation", "animators",
                        [](ecs::Registry& registry, float dt) { AnimateEntities(registry, dt); });
}

}  // namespace rtrt::physics
