#pragma once
// What the contact passes need of one contact point, computed from the bodies at the start of the
// passes. The GPU solver (gpu_contact_solver.h) runs this code; the CPU rows do the same operations
// in the same order eight contacts at a time (contact_row_setup.h), and with contraction off on
// both (-ffp-contract=off, -fmad=false) they get the same bits (contact_rows_test checks them).
#include <glm/mat3x3.hpp>

#include "engine/core/math.h"
#include "engine/physics_anim/orthonormal_basis.h"
#include "engine/physics_anim/solver_types.h"

namespace rtrt::physics {

// Effective mass of the contact along direction: the inverse of the relative speed along it that
// a unit impulse along it makes.
RT_HD inline float AxisMass(const SolverBody& a, const SolverBody& b, vec3 rA, vec3 rB,
                            vec3 direction) {
    const vec3 armA = glm::cross(rA, direction);
    const vec3 armB = glm::cross(rB, direction);
    const float k = a.invMass + b.invMass + glm::dot(armA, a.invInertia * armA) +
                    glm::dot(armB, b.invInertia * armB);
    return k > 0.0f ? 1.0f / k : 0.0f;
}

struct ContactSetUp {
    vec3 tangent1{0.0f};
    vec3 tangent2{0.0f};
    vec3 anchorA{0.0f};  // the contact point less body a's centre
    vec3 anchorB{0.0f};
    float normalMass = 0.0f;
    float tangentMass1 = 0.0f;
    float tangentMass2 = 0.0f;
    float friction = 0.0f;
    float allowedApproach = 0.0f;  // speed at which a speculative contact may close
    float overlap = 0.0f;          // beyond the linear slop, for the position iterations
    float bounce = 0.0f;           // the speed restitution leaves at (0: none)
    float rollingLimit = 0.0f;     // 0: no rolling resistance (or neither body can turn)
    glm::mat3 rollingMass{0.0f};
};

// Contact c between bodies a and b (by slot: their state at the start of the step, and as the
// solver sees them).
RT_HD inline ContactSetUp SetUpContact(const Contact& c, const BodyAtStart& a, const BodyAtStart& b,
                                       const SolverBody& sa, const SolverBody& sb,
                                       const SolverSettings& settings) {
    ContactSetUp out;
    out.anchorA = c.point - a.position;
    out.anchorB = c.point - b.position;
    OrthonormalBasis(c.normal, out.tangent1, out.tangent2);
    out.normalMass = AxisMass(sa, sb, out.anchorA, out.anchorB, c.normal);
    out.tangentMass1 = AxisMass(sa, sb, out.anchorA, out.anchorB, out.tangent1);
    out.tangentMass2 = AxisMass(sa, sb, out.anchorA, out.anchorB, out.tangent2);
    out.friction = sqrtf(a.friction * b.friction);
    out.allowedApproach = c.separation > 0.0f ? c.separation / settings.dt : 0.0f;
    out.overlap = -c.separation - settings.linearSlop;
    // Restitution: the approach speed at the start of the step, before gravity.
    const vec3 startRelative = b.velocity + glm::cross(b.angularVelocity, out.anchorB) -
                               a.velocity - glm::cross(a.angularVelocity, out.anchorA);
    const float approach = -glm::dot(startRelative, c.normal);
    if (approach > settings.restitutionThreshold) {
        const float gravitySpeed = fabsf(glm::dot(settings.gravity, c.normal)) * settings.dt;
        const float restitution = a.restitution < b.restitution ? b.restitution : a.restitution;
        const float bounce = restitution * approach - gravitySpeed;
        out.bounce = bounce < 0.0f ? 0.0f : bounce;
    }
    if (c.rollingLimit > 0.0f) {
        const glm::mat3 inverse = sa.invInertia + sb.invInertia;
        if (glm::determinant(inverse) > 0.0f) {  // else neither body can turn
            out.rollingLimit = c.rollingLimit;
            out.rollingMass = glm::inverse(inverse);
        }
    }
    return out;
}

}  // namespace rtrt::physics
