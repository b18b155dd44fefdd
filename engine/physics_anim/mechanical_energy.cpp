// PhysicsWorld::MechanicalEnergy: what the energy tests and tools measure, apart from the step.
#include "engine/physics_anim/physics_world.h"

namespace rtrt::physics {

using ecs::Entity;
using ecs::Registry;

double PhysicsWorld::MechanicalEnergy(const Registry& registry) const {
    double energy = 0.0;
    const glm::dvec3 gravity(settings_.gravity);
    registry.View<const RigidBody, const LocalTransform>().Each(
        [&](Entity e, const RigidBody& rb, const LocalTransform& local) {
            const Collider* collider = registry.Get<Collider>(e);
            if (rb.mass <= 0.0f || (collider && collider->shape == ColliderShape::kPlane)) return;
            const bool placed = rb.state.initialized;
            const glm::dvec3 position(placed ? rb.state.position : local.translation);
            const glm::quat orientation = placed ? rb.state.orientation : local.rotation;
            const glm::dvec3 v(rb.velocity);
            energy += 0.5 * rb.mass * glm::dot(v, v) - rb.mass * glm::dot(gravity, position);
            if (collider != nullptr) {
                const glm::dvec3 inertia(InertiaDiagonal(*collider, rb.mass));
                const glm::dvec3 w(glm::conjugate(orientation) * rb.angularVelocity);  // body frame
                energy += 0.5 * glm::dot(inertia, w * w);
            }
        });
    return energy;
}

}  // namespace rtrt::physics
