#pragma once
// What the contact solver (contact_solver.h) and its rows (contact_rows.h) share: the bodies as
// the solver sees them, the contacts and the settings.
#include <cstdint>
#include <glm/mat3x3.hpp>

#include "engine/core/math.h"

namespace rtrt::physics {

// What an iteration reads and writes of a body, in one 64-byte cache line of its own: the
// solver's passes stream the rows and hit these at random, so 10,000 of them stay in a core's
// cache, and threads writing neighbouring bodies do not share a line. A body that is not awake
// has zero inverse mass and inertia and is never written.
struct alignas(64) SolverBody {
    vec3 velocity{0.0f};
    float invMass = 0.0f;
    vec3 angularVelocity{0.0f};
    glm::mat3 invInertia{0.0f};  // world space
};

// What setting up a contact reads of a body, by slot like SolverBody: one 48-byte record
// instead of four scattered fields of a SimBody.
struct alignas(16) BodyAtStart {
    vec3 position{0.0f};
    float friction = 0.0f;
    vec3 velocity{0.0f};  // at the start of the step, before gravity: restitution uses it
    float restitution = 0.0f;
    vec3 angularVelocity{0.0f};
};

// Split impulse: moves a body out of overlap during the step, adds no speed. Aligned like
// SolverBody, for the same reason.
struct alignas(32) PseudoVelocity {
    vec3 linear{0.0f};
    vec3 angular{0.0f};
};

// A contact point as the narrow phase finds it, with the impulses that warm-start it (seeded
// from the last step, zero otherwise) and, after SolveContacts, the impulses it solved to.
struct Contact {
    uint32_t a;  // body indices; the normal points from a to b
    uint32_t b;
    vec3 normal;
    vec3 point;
    float separation;    // at the start of the step; negative when overlapping
    float rollingLimit;  // max rolling impulse per unit normal impulse, in metres (0: none)
    float normalImpulse;
    float tangentImpulse1;
    float tangentImpulse2;
};

struct SolverSettings {
    float dt;
    vec3 gravity;
    int velocityIterations;
    int positionIterations;
    float restitutionThreshold;
    float linearSlop;
    float positionCorrection;
};

}  // namespace rtrt::physics
