#pragma once
// Transform components: the pose an entity has relative to its parent, the parent link, and the
// object-to-world matrix the transform system derives from them.
#include <glm/gtc/quaternion.hpp>

#include "engine/core/math.h"
#include "engine/ecs/entity.h"

namespace rtrt::physics {

// Pose relative to the parent (or the world, for a root): scale, then rotate, then translate.
// Whoever writes it calls Registry::MarkChanged<LocalTransform> so that the transform system
// recomputes the entity's world transform and its descendants'.
struct LocalTransform {
    vec3 translation{0.0f};
    glm::quat rotation = glm::identity<glm::quat>();
    vec3 scale{1.0f};
};

// The entity whose world transform this entity's LocalTransform is relative to. Set it through
// SetParent (transform_system.h), which rejects cycles.
struct Parent {
    ecs::Entity entity;
};

// Derived by the transform system and marked changed when it is rewritten, so extraction uploads
// only the instances that moved.
struct WorldTransform {
    glm::mat4 objectToWorld{1.0f};
};

inline glm::mat4 ToMatrix(const LocalTransform& t) {
    glm::mat4 m = glm::mat4_cast(t.rotation);
    m[0] *= t.scale.x;
    m[1] *= t.scale.y;
    m[2] *= t.scale.z;
    m[3] = glm::vec4(t.translation, 1.0f);
    return m;
}

}  // namespace rtrt::physics
