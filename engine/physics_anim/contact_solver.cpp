#include "engine/physics_anim/contact_solver.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "engine/core/parallel_for.h"
#include "engine/physics_anim/procedural_motion.h"

namespace rtrt::physics {

namespace {

ContactAxis MakeAxis(const SimBody& a, const SimBody& b, const Contact& c, vec3 rA, vec3 rB,
                     vec3 direction) {
    ContactAxis axis;
    axis.direction = direction;
    axis.armA = glm::cross(rA, direction);
    axis.armB = glm::cross(rB, direction);
    axis.turnA = a.invInertiaWorld * axis.armA;
    axis.turnB = b.invInertiaWorld * axis.armB;
    const float k =
        c.invMassA + c.invMassB + glm::dot(axis.armA, axis.turnA) + glm::dot(axis.armB, axis.turnB);
    axis.mass = k > 0.0f ? 1.0f / k : 0.0f;
    return axis;
}

float Speed(const SimBody& a, const SimBody& b, const ContactAxis& axis) {
    return glm::dot(axis.direction, b.velocity - a.velocity) +
           glm::dot(b.angularVelocity, axis.armB) - glm::dot(a.angularVelocity, axis.armA);
}

float PseudoSpeed(const SimBody& a, const SimBody& b, const ContactAxis& axis) {
    return glm::dot(axis.direction, b.pseudoVelocity - a.pseudoVelocity) +
           glm::dot(b.pseudoAngularVelocity, axis.armB) -
           glm::dot(a.pseudoAngularVelocity, axis.armA);
}

// Applies impulse along the axis to b and its opposite to a. A body that is not awake has zero
// inverse mass in the contact and is not written: other manifolds of the same colour may read it
// at the same time.
void Push(SimBody& a, SimBody& b, const Contact& c, const ContactAxis& axis, float impulse) {
    if (c.invMassA > 0.0f) {
        a.velocity -= (c.invMassA * impulse) * axis.direction;
        a.angularVelocity -= impulse * axis.turnA;
    }
    if (c.invMassB > 0.0f) {
        b.velocity += (c.invMassB * impulse) * axis.direction;
        b.angularVelocity += impulse * axis.turnB;
    }
}

// Manifolds per task: a box manifold's iteration is a few dozen dot products.
constexpr size_t kManifoldGrain = 64;

// Calls solve(contact) for every contact, colour after colour, the manifolds of a colour in
// parallel and each manifold's contacts in order on one thread.
template <typename ContactType, typename Solve>
void ForEachContact(std::span<ContactType> contacts, const ContactBatches& batches,
                    const Solve& solve) {
    const auto solveManifolds = [&](size_t begin, size_t end) {
        for (uint32_t k = batches.manifoldBegin[begin]; k < batches.manifoldBegin[end]; ++k) {
            solve(contacts[k]);
        }
    };
    for (uint32_t color = 0; color < batches.Colors(); ++color) {
        const uint32_t begin = batches.colorBegin[color];
        const uint32_t end = batches.colorBegin[color + 1];
        if (batches.lastIsOverflow && color + 1 == batches.Colors()) {
            solveManifolds(begin, end);
            continue;
        }
        tbb::parallel_for(
            tbb::blocked_range<size_t>(begin, end, kManifoldGrain),
            [&](const tbb::blocked_range<size_t>& r) { solveManifolds(r.begin(), r.end()); });
    }
}

}  // namespace

void PrepareContacts(std::span<const SimBody> bodies, std::span<Contact> contacts,
                     const SolverSettings& settings) {
    ParallelFor(0, contacts.size(), 256, [&](size_t k) {
        Contact& c = contacts[k];
        const SimBody& a = bodies[c.a];
        const SimBody& b = bodies[c.b];
        c.invMassA = a.awake ? a.invMass : 0.0f;
        c.invMassB = b.awake ? b.invMass : 0.0f;
        const vec3 rA = c.point - a.position;
        const vec3 rB = c.point - b.position;
        vec3 t1;
        vec3 t2;
        OrthonormalBasis(c.normal, t1, t2);
        c.normalAxis = MakeAxis(a, b, c, rA, rB, c.normal);
        c.tangentAxis1 = MakeAxis(a, b, c, rA, rB, t1);
        c.tangentAxis2 = MakeAxis(a, b, c, rA, rB, t2);
        c.normalImpulse = 0.0f;
        c.tangentImpulse1 = 0.0f;
        c.tangentImpulse2 = 0.0f;
        c.pseudoImpulse = 0.0f;
        c.rollingImpulse = vec3(0.0f);
        c.rollingMass = glm::mat3(0.0f);
        if (c.rollingLimit > 0.0f) {
            const glm::mat3 k = a.invInertiaWorld + b.invInertiaWorld;
            if (glm::determinant(k) > 0.0f) {
                c.rollingMass = glm::inverse(k);
            } else {
                c.rollingLimit = 0.0f;  // neither body can turn
            }
        }
        const vec3 startRelative = b.startVelocity + glm::cross(b.startAngularVelocity, rB) -
                                   a.startVelocity - glm::cross(a.startAngularVelocity, rA);
        c.approachSpeed = -glm::dot(startRelative, c.normal);
        c.gravitySpeed = std::fabs(glm::dot(settings.gravity, c.normal)) * settings.dt;
        c.restitution = std::max(a.restitution, b.restitution);
        c.friction = std::sqrt(a.friction * b.friction);
    });
}

void WarmStart(std::span<SimBody> bodies, std::span<const Contact> contacts,
               const ContactBatches& batches) {
    ForEachContact(contacts, batches, [&](const Contact& c) {
        SimBody& a = bodies[c.a];
        SimBody& b = bodies[c.b];
        Push(a, b, c, c.normalAxis, c.normalImpulse);
        Push(a, b, c, c.tangentAxis1, c.tangentImpulse1);
        Push(a, b, c, c.tangentAxis2, c.tangentImpulse2);
    });
}

void SolveVelocities(std::span<SimBody> bodies, std::span<Contact> contacts,
                     const ContactBatches& batches, const SolverSettings& settings) {
    const float invDt = 1.0f / settings.dt;
    for (int iteration = 0; iteration < settings.velocityIterations; ++iteration) {
        ForEachContact(contacts, batches, [&](Contact& c) {
            SimBody& a = bodies[c.a];
            SimBody& b = bodies[c.b];
            if (c.rollingLimit > 0.0f && c.normalImpulse > 0.0f) {
                const vec3 spin = b.angularVelocity - a.angularVelocity;
                vec3 rolling = c.rollingImpulse - c.rollingMass * spin;
                const float maxRolling = c.rollingLimit * c.normalImpulse;
                const float length = glm::length(rolling);
                if (length > maxRolling) rolling *= maxRolling / length;
                const vec3 delta = rolling - c.rollingImpulse;
                c.rollingImpulse = rolling;
                if (a.awake) a.angularVelocity -= a.invInertiaWorld * delta;
                if (b.awake) b.angularVelocity += b.invInertiaWorld * delta;
            }
            // Friction before the normal, so that the normal constraint, which matters more, is
            // solved last.
            const float maxFriction = c.friction * c.normalImpulse;
            if (maxFriction > 0.0f) {
                float t1 = c.tangentImpulse1 - c.tangentAxis1.mass * Speed(a, b, c.tangentAxis1);
                float t2 = c.tangentImpulse2 - c.tangentAxis2.mass * Speed(a, b, c.tangentAxis2);
                const float length = std::sqrt(t1 * t1 + t2 * t2);
                if (length > maxFriction) {  // clamp to the friction cone
                    t1 *= maxFriction / length;
                    t2 *= maxFriction / length;
                }
                Push(a, b, c, c.tangentAxis1, t1 - c.tangentImpulse1);
                Push(a, b, c, c.tangentAxis2, t2 - c.tangentImpulse2);
                c.tangentImpulse1 = t1;
                c.tangentImpulse2 = t2;
            }
            const float vn = Speed(a, b, c.normalAxis);
            const float allowedApproach = c.separation > 0.0f ? c.separation * invDt : 0.0f;
            const float impulse =
                std::max(c.normalImpulse - c.normalAxis.mass * (vn + allowedApproach), 0.0f);
            Push(a, b, c, c.normalAxis, impulse - c.normalImpulse);
            c.normalImpulse = impulse;
        });
    }
}

void ApplyRestitution(std::span<SimBody> bodies, std::span<Contact> contacts,
                      const ContactBatches& batches, const SolverSettings& settings) {
    ForEachContact(contacts, batches, [&](Contact& c) {
        if (c.normalImpulse <= 0.0f || c.approachSpeed <= settings.restitutionThreshold) return;
        const float target = c.restitution * c.approachSpeed - c.gravitySpeed;
        if (target <= 0.0f) return;
        SimBody& a = bodies[c.a];
        SimBody& b = bodies[c.b];
        const float vn = Speed(a, b, c.normalAxis);
        const float impulse = std::max(c.normalImpulse - c.normalAxis.mass * (vn - target), 0.0f);
        Push(a, b, c, c.normalAxis, impulse - c.normalImpulse);
        c.normalImpulse = impulse;
    });
}

void SolvePositions(std::span<SimBody> bodies, std::span<Contact> contacts,
                    const ContactBatches& batches, const SolverSettings& settings) {
    const float rate = settings.positionCorrection / settings.dt;
    for (int iteration = 0; iteration < settings.positionIterations; ++iteration) {
        ForEachContact(contacts, batches, [&](Contact& c) {
            const float overlap = -c.separation - settings.linearSlop;
            if (overlap <= 0.0f) return;
            SimBody& a = bodies[c.a];
            SimBody& b = bodies[c.b];
            const float vn = PseudoSpeed(a, b, c.normalAxis);
            const float impulse =
                std::max(c.pseudoImpulse - c.normalAxis.mass * (vn - rate * overlap), 0.0f);
            const float delta = impulse - c.pseudoImpulse;
            c.pseudoImpulse = impulse;
            const vec3 p = delta * c.normalAxis.direction;
            if (c.invMassA > 0.0f) {
                a.pseudoVelocity -= c.invMassA * p;
                a.pseudoAngularVelocity -= delta * c.normalAxis.turnA;
            }
            if (c.invMassB > 0.0f) {
                b.pseudoVelocity += c.invMassB * p;
                b.pseudoAngularVelocity += delta * c.normalAxis.turnB;
            }
        });
    }
}

}  // namespace rtrt::physics
