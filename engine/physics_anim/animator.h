#pragma once
// The Animator component and the system that poses animated entities each frame.
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/ecs/registry.h"
#include "engine/ecs/scheduler.h"
#include "engine/physics_anim/keyframe_track.h"
#include "engine/physics_anim/procedural_motion.h"
#include "engine/physics_anim/transform.h"

namespace rtrt::physics {

// Poses an entity from base: the clip (if any) overwrites the channels it has keys for, then the
// motions apply in order (so Orbit then Spin circles while turning; Bob after Orbit bobs the
// orbit). The entity needs a LocalTransform, which the animation system overwrites; an entity
// should not also have a dynamic RigidBody, whose pose the animation would override.
struct Animator {
    std::shared_ptr<const KeyframeClip> clip;
    std::vector<ProceduralMotion> motions;
    LocalTransform base;
    // Added to the clip's translation keys: a spawner's copies share one clip, each played at its
    // own place.
    vec3 keyOffset{0.0f};
    // Where a user put the entity (the window's drag and turn: PlaceAnimated), applied last: the
    // animated translation is moved by `moved` and its rotation turned by `turned`, so that the
    // edit lasts while the animation plays on from there.
    vec3 moved{0.0f};
    glm::quat turned = glm::identity<glm::quat>();
    double time = 0.0;    // seconds of animation played
    float speed = 1.0f;   // playback rate: time advances by speed * dt
    bool playing = true;  // a paused animator is not touched at all
};

// Advances every playing Animator by dt, writes its entity's LocalTransform and marks it
// changed where the pose differs from what it held (a finished clip or a spin of speed 0 hands
// nothing on). Only entities with both components are visited (the view walks the smaller pool),
// so the cost follows the number of animators. Returns how many entities were posed.
uint32_t AnimateEntities(ecs::Registry& registry, float dt);

// The pose an animator gives at its current time.
LocalTransform EvaluateAnimator(const Animator& animator);

// Sets the animator's user placement (moved, turned) so that it poses its entity at position and
// rotation now; the animation goes on from there.
void PlaceAnimated(Animator& animator, vec3 position, glm::quat rotation);

// Adds AnimateEntities to phase "animation" under the name "animators".
void AddAnimationSystem(ecs::Scheduler& scheduler);

}  // namespace rtrt::physics
