#pragma once
// Registers the module's systems in the scheduler's phases, in the order they must run.
#include "engine/ecs/scheduler.h"
#include "engine/physics_anim/physics_world.h"
#include "engine/physics_anim/transform_system.h"

namespace rtrt::physics {

// "simulation": physics (writes dynamic bodies' LocalTransform); "animation": animators (write
// animated LocalTransforms), morph weights (follow their animators' clocks), then transforms
// (derive WorldTransform from every LocalTransform changed this frame), then skins (joint
// matrices from this frame's world transforms), so that "extraction" sees this frame's poses.
void AddPhysicsAnimSystems(ecs::Scheduler& scheduler, PhysicsWorld& physics,
                           TransformSystem& transforms);

}  // namespace rtrt::physics
