#pragma once
// Waking what rested on a body that is about to be removed.
#include <cstdint>

#include "engine/ecs/registry.h"

namespace rtrt::physics {

// Wakes the sleeping bodies that may rest on or lean against body E, which is about to go or be
// moved by hand (the window's Delete and drag: World::Remove, SetPose): those whose bounding
// sphere comes within MARGIN of E's, or, for a plane, of its half-space, where E is and where the
// last step saw it. Asleep, they would have stayed in the air where it was, since a sleeper
// wakes only when something near it moves. Returns how many were woken.
uint32_t WakeSleepersAround(ecs::Registry& registry, ecs::Entity e, float margin);

}  // namespace rtrt::physics
