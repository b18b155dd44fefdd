#pragma once
// Registers the module's systems in the scheduler's phases, in the order they must run.
#include "engine/ecs/scheduler.h"
#include "engine/physics_anim/physics_world.h"
#include "engine/physics_anim/transform_system.h"

namespace rtrt::physics {

// "simulation": physics (writes dynamic bodies' LocalTransform); "animation": animators (write
// animated LocalTransforms), morph weights (follow their animators' clocks), then transforms
// (derive WorldTransform from every LocalTransform changed this frame); "extraction": skins
// (joint matrices from this frame's world transforms), so that the frame's extraction sees this
// frame's poses. Skins run a phase later because a mesh or joint created since the last frame
// gets its WorldTransform only when the animation phase ends (an Add, deferred).
void AddPhysicsAnimSystems(ecs::Scheduler& scheduler, PhysicsWorld& physics,
                           TransformSystem& transforms);

}  // namespace rtrt::physics
