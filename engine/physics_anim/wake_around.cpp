#include "engine/physics_anim/wake_around.h"

#include <algorithm>
#include <glm/gtc/quaternion.hpp>
#include <vector>

#include "engine/physics_anim/collider.h"
#include "engine/physics_anim/rigid_body.h"
#include "engine/physics_anim/transform.h"

namespace rtrt::physics {

uint32_t WakeSleepersAround(ecs::Registry& registry, ecs::Entity e, float margin) {
    const Collider* leaving = registry.Get<Collider>(e);
    const LocalTransform* place = registry.Get<LocalTransform>(e);
    const RigidBody* leavingBody = registry.Get<RigidBody>(e);
    if (!leaving || !place || !leavingBody) return 0;
    // Where it is now and where the last step saw it (an edit since may have moved it: a drag,
    // then Delete before a step).
    struct Pose {
        vec3 position;
        glm::quat rotation;
    };
    std::vector<Pose> poses{{place->translation, place->rotation}};
    if (leavingBody->state.initialized)
        poses.push_back({leavingBody->state.position, leavingBody->state.orientation});
    const bool plane = leaving->shape == ColliderShape::kPlane;
    const float radius = BoundingRadius(*leaving);
    uint32_t woken = 0;
    registry.View<RigidBody, LocalTransform>().Each(
        [&](ecs::Entity other, RigidBody& body, LocalTransform& local) {
            if (other == e || !body.state.sleeping) return;
            const Collider* collider = registry.Get<Collider>(other);
            if (!collider || collider->shape == ColliderShape::kPlane) return;
            const float reach = BoundingRadius(*collider) + margin;
            const bool touching = std::any_of(poses.begin(), poses.end(), [&](const Pose& pose) {
                const vec3 offset = local.translation - pose.position;
                if (!plane) return glm::length(offset) <= radius + reach;
                const vec3 normal = glm::normalize(glm::normalize(pose.rotation) * leaving->normal);
                return glm::dot(normal, offset) < reach;
            });
            if (!touching) return;
            WakeUp(body);
            ++woken;
        });
    return woken;
}

}  // namespace rtrt::physics
