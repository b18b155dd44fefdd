#include "engine/physics_anim/wake_around.h"

#include <glm/gtc/quaternion.hpp>

#include "engine/physics_anim/collider.h"
#include "engine/physics_anim/rigid_body.h"
#include "engine/physics_anim/transform.h"

namespace rtrt::physics {

uint32_t WakeSleepersAround(ecs::Registry& registry, ecs::Entity e, float margin) {
    const Collider* leaving = registry.Get<Collider>(e);
    const LocalTransform* place = registry.Get<LocalTransform>(e);
    if (!leaving || !place || !registry.Has<RigidBody>(e)) return 0;
    const bool plane = leaving->shape == ColliderShape::kPlane;
    const vec3 normal = glm::normalize(glm::normalize(place->rotation) * leaving->normal);
    const float radius = BoundingRadius(*leaving);
    uint32_t woken = 0;
    registry.View<RigidBody, LocalTransform>().Each(
        [&](ecs::Entity other, RigidBody& body, LocalTransform& local) {
            if (other == e || !body.state.sleeping) return;
            const Collider* collider = registry.Get<Collider>(other);
            if (!collider || collider->shape == ColliderShape::kPlane) return;
            const float reach = BoundingRadius(*collider) + margin;
            const vec3 offset = local.translation - place->translation;
            const bool touching =
                plane ? glm::dot(normal, offset) < reach : glm::length(offset) <= radius + reach;
            if (!touching) return;
            WakeUp(body);
            ++woken;
        });
    return woken;
}

}  // namespace rtrt::physics
