#pragma once
// The "animate" field of a scene file's instances and spawners: procedural motions (orbit, spin,
// bob) and keyframes.
#include <string>

#include "engine/physics_anim/animator.h"
#include "game/scene/json_fields.h"

namespace rtrt {

// Rotation by degrees about x, then y, then z (the scene files' convention).
glm::quat EulerDegrees(vec3 degrees);

// The animator J (at PATH of FILE) asks for, starting from the entity's pose BASE. Throws
// InputError naming the field for anything malformed.
physics::Animator ParseAnimator(const Json& j, const std::string& path,
                                const physics::LocalTransform& base, const std::string& file);

}  // namespace rtrt
