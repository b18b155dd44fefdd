#include "engine/physics_anim/physics_anim_systems.h"

#include "engine/physics_anim/animator.h"
#include "engine/physics_anim/skinning.h"

namespace rtrt::physics {

void AddPhysicsAnimSystems(ecs::Scheduler& scheduler, PhysicsWorld& physics,
                           TransformSystem& transforms) {
    AddPhysicsSystem(scheduler, physics);
    AddAnimationSystem(scheduler);
    AddMorphWeightsSystem(scheduler);
    AddTransformSystem(scheduler, transforms);
    AddSkinSystem(scheduler);
}

}  // namespace rtrt::physics
