#include "engine/physics_anim/physics_anim_systems.h"

#include "engine/physics_anim/animator.h"

namespace rtrt::physics {

void AddPhysicsAnimSystems(ecs::Scheduler& scheduler, PhysicsWorld& physics,
                           TransformSystem& transforms) {
    AddPhysicsSystem(scheduler, physics);
    AddAnimationSystem(scheduler);
    AddTransformSystem(scheduler, transforms);
}

}  // namespace rtrt::physics
