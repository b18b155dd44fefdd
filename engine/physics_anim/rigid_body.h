#pragma once
// The RigidBody component: mass properties and material set by the user, motion state kept by
// the PhysicsWorld.
#include <glm/gtc/quaternion.hpp>

#include "engine/core/math.h"

namespace rtrt::physics {

// A body takes part in the simulation when its entity has a RigidBody and a LocalTransform; a
// Collider (collider.h) makes it collide. Bodies are roots: their LocalTransform is treated as
// the world pose (a Parent is ignored).
//
// mass 0 makes the body static: it never moves by itself, and its pose is read from its
// LocalTransform every frame, so moving it there teleports it. A dynamic body's pose lives in
// `state`; the world writes the LocalTransform (interpolated between steps) from it. Place a
// body through its LocalTransform before its first step, later with Teleport.
struct RigidBody {
    float mass = 1.0f;           // kilograms; 0 = static
    vec3 velocity{0.0f};         // m/s, of the centre
    vec3 angularVelocity{0.0f};  // rad/s, world frame
    // Pairwise: the larger restitution and the geometric mean of the frictions apply.
    float restitution = 0.3f;  // 0 = no bounce, 1 = elastic (see PhysicsSettings)
    float friction = 0.5f;     // Coulomb coefficient
    // Resists the rolling (and spinning) of a sphere in contact: the torque is at most
    // rollingResistance * radius * normal force. Without it a ball rolls forever and never sleeps.
    float rollingResistance = 0.02f;
    bool fixedRotation = false;  // ignore torques: the body keeps its angular velocity

    // A dynamic body's simulated pose; a static body's is where the last step saw it.
    struct State {
        vec3 position{0.0f};
        glm::quat orientation = glm::identity<glm::quat>();
        vec3 previousPosition{0.0f};  // at the start of the last step, for interpolation
        glm::quat previousOrientation = glm::identity<glm::quat>();
        float restingTime = 0.0f;  // seconds the body has been slower than the sleep speeds
        bool sleeping = false;
        bool initialized = false;  // false until the world has read the LocalTransform
    } state;
};

// Moves a dynamic body to a pose at once (no interpolation from the old one) and wakes it.
inline void Teleport(RigidBody& body, vec3 position, glm::quat orientation) {
    body.state.position = body.state.previousPosition = position;
    body.state.orientation = body.state.previousOrientation = orientation;
    body.state.restingTime = 0.0f;
    body.state.sleeping = false;
    body.state.initialized = true;
}

// A sleeping body is also woken by giving it a velocity, or by a moving body touching it.
inline void WakeUp(RigidBody& body) {
    body.state.restingTime = 0.0f;
    body.state.sleeping = false;
}

}  // namespace rtrt::physics
