#pragma once
// Sequential impulses over the step's contacts (Catto 2005, "Iterative Dynamics with Temporal
// Coherence"): warm starting, Coulomb friction, rolling resistance, speculative contacts,
// restitution, and split-impulse position correction.
#include <cstdint>
#include <glm/mat3x3.hpp>
#include <span>

#include "engine/physics_anim/contact_coloring.h"
#include "engine/physics_anim/sim_body.h"

namespace rtrt::physics {

// One direction of a contact's constraint, with the lever arms precomputed so that an iteration
// costs dot products: the relative speed along it is
// dot(direction, vB - vA) + dot(wB, armB) - dot(wA, armA).
struct ContactAxis {
    vec3 direction;
    vec3 armA;   // rA x direction
    vec3 armB;   // rB x direction
    vec3 turnA;  // change of wA per unit impulse: invInertiaA * armA (zero when A is not awake)
    vec3 turnB;
    float mass;  // effective mass along the direction
};

struct Contact {
    uint32_t a;  // body indices; the normal points from a to b
    uint32_t b;
    vec3 normal;
    vec3 point;
    float separation;    // at the start of the step; negative when overlapping
    float rollingLimit;  // max rolling impulse per unit normal impulse, in metres (0: none)

    // Filled by PrepareContacts (the impulses zeroed; the caller may seed them, see WarmStart).
    ContactAxis normalAxis;
    ContactAxis tangentAxis1;
    ContactAxis tangentAxis2;
    float invMassA;  // zero for a body that is not awake
    float invMassB;
    float normalImpulse;
    float tangentImpulse1;
    float tangentImpulse2;
    float pseudoImpulse;
    vec3 rollingImpulse;
    glm::mat3 rollingMass;  // inverse of the summed inverse inertias
    float approachSpeed;    // normal speed of approach at the start of the step, before gravity
    float gravitySpeed;  // |gravity . normal| * dt: what gravity can add to the approach in a step
    float restitution;
    float friction;
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

// Each pass below runs the colours of batches one after another and the manifolds of a colour in
// parallel (TBB); only bodies that are awake are written. The result does not depend on the
// number of threads.
void PrepareContacts(std::span<const SimBody> bodies, std::span<Contact> contacts,
                     const SolverSettings& settings);

// Applies the contacts' seeded impulses, so that the iterations start from last step's solution:
// resting stacks converge in a few iterations instead of sinking.
void WarmStart(std::span<SimBody> bodies, std::span<const Contact> contacts,
               const ContactBatches& batches);

// Rolling resistance, friction within the Coulomb cone and a non-negative normal impulse that
// lets a speculative contact (separation > 0) close its gap within the step but not overshoot it.
void SolveVelocities(std::span<SimBody> bodies, std::span<Contact> contacts,
                     const ContactBatches& batches, const SolverSettings& settings);

// One pass after SolveVelocities (as Box2D v3 does): a touching contact whose approach speed u
// exceeds the threshold leaves at e * u - |g . n| * dt. Dropping one step's worth of gravity from
// the rebound means that a bounce never gains energy (a ball that reached the contact at the
// start of the step would otherwise also keep the speed gravity gave it during the step).
void ApplyRestitution(std::span<SimBody> bodies, std::span<Contact> contacts,
                      const ContactBatches& batches, const SolverSettings& settings);

// Split impulse: pseudo velocities push overlapping bodies apart by positionCorrection of the
// overlap beyond linearSlop per step; they move the bodies but are discarded afterwards, so the
// correction adds no kinetic energy (unlike Baumgarte stabilisation of the velocities).
void SolvePositions(std::span<SimBody> bodies, std::span<Contact> contacts,
                    const ContactBatches& batches, const SolverSettings& settings);

}  // namespace rtrt::physics
