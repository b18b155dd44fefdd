#pragma once
// A body as the physics step sees it: copied from the components when a frame's steps begin and
// copied back when they end, so the steps run over one packed array.
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "engine/ecs/entity.h"
#include "engine/physics_anim/collider.h"
#include "engine/physics_anim/rigid_body.h"
#include "engine/physics_anim/transform.h"

namespace rtrt::physics {

struct SimBody {
    ecs::Entity entity;
    RigidBody* body = nullptr;  // the components, valid while the frame's steps run
    LocalTransform* local = nullptr;
    Collider collider;
    bool hasCollider = false;
    bool dynamic = false;  // mass > 0 and not a plane
    bool awake = false;    // dynamic and not sleeping: only awake bodies move
    bool fresh = false;    // static and placed or moved since the last step: it wakes sleepers

    vec3 position{0.0f};
    glm::quat orientation = glm::identity<glm::quat>();
    glm::mat3 rotation{1.0f};  // of orientation, refreshed at the start of each step
    vec3 previousPosition{0.0f};
    glm::quat previousOrientation = glm::identity<glm::quat>();
    vec3 velocity{0.0f};
    vec3 angularVelocity{0.0f};
    vec3 startVelocity{0.0f};  // at the start of the step, before gravity: restitution uses it
    vec3 startAngularVelocity{0.0f};

    float invMass = 0.0f;             // of a dynamic body; the solver uses 0 for one not awake
    vec3 invInertiaLocal{0.0f};       // principal, zero for fixed rotation
    glm::mat3 invInertiaWorld{0.0f};  // zero when not awake
    float boundingRadius = 0.0f;
    float rollingResistance = 0.0f;  // beside the bounding radius: the narrow phase reads both
    float restitution = 0.0f;
    float friction = 0.0f;
    float restingTime = 0.0f;
};

// The inverse inertia tensor in world axes: R diag(invInertiaLocal) R^T.
inline glm::mat3 WorldInverseInertia(const glm::mat3& rotation, vec3 invInertiaLocal) {
    glm::mat3 scaled = rotation;
    scaled[0] *= invInertiaLocal.x;
    scaled[1] *= invInertiaLocal.y;
    scaled[2] *= invInertiaLocal.z;
    return scaled * glm::transpose(rotation);
}

}  // namespace rtrt::physics
