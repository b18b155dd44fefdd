#include "engine/physics_anim/contact_row_setup.h"

#include <cstddef>

#include "engine/physics_anim/body_lanes.h"
#include "engine/physics_anim/lanes.h"

namespace rtrt::physics {

namespace {

// What setting up a row reads of its eight contacts and of the bodies at the start of the passes.
struct ContactLanes {
    Lanes3 normal;
    Lanes3 point;
    Lanes separation;
    Lanes rollingLimit;
    Lanes normalImpulse;
    Lanes tangentImpulse1;
    Lanes tangentImpulse2;
};
struct StartLanes {
    Lanes3 position;
    Lanes friction;
    Lanes3 velocity;
    Lanes restitution;
    Lanes3 angularVelocity;
};

static_assert(offsetof(Contact, normal) == 2 * sizeof(float) &&
              offsetof(Contact, point) == 5 * sizeof(float) &&
              offsetof(Contact, separation) == 8 * sizeof(float) &&
              offsetof(Contact, rollingLimit) == 9 * sizeof(float) &&
              offsetof(Contact, normalImpulse) == 10 * sizeof(float) &&
              offsetof(Contact, tangentImpulse2) == 12 * sizeof(float) &&
              sizeof(Contact) == 13 * sizeof(float));
static_assert(offsetof(BodyAtStart, friction) == 3 * sizeof(float) &&
              offsetof(BodyAtStart, velocity) == 4 * sizeof(float) &&
              offsetof(BodyAtStart, restitution) == 7 * sizeof(float) &&
              offsetof(BodyAtStart, angularVelocity) == 8 * sizeof(float) &&
              sizeof(BodyAtStart) == 12 * sizeof(float));

// Floats [first, first + 8) of each lane's record, records[l] being a T.
template <typename T>
[[gnu::always_inline]] inline void GatherFrom(const T* const (&records)[kLanes], int first,
                                              Lanes (&out)[8]) {
    const float* floats[kLanes];
    for (int l = 0; l < kLanes; ++l) floats[l] = reinterpret_cast<const float*>(records[l]) + first;
    GatherColumns(floats, out);
}

[[gnu::always_inline]] inline ContactLanes GatherContacts(
    const Contact* const (&contacts)[kLanes]) {
    Lanes low[8];
    Lanes high[8];
    GatherFrom(contacts, 2, low);   // normal, point, separation, rolling limit
    GatherFrom(contacts, 5, high);  // point, separation, rolling limit, the impulses
    return {{low[0], low[1], low[2]},
            {low[3], low[4], low[5]},
            low[6],
            low[7],
            high[5],
            high[6],
            high[7]};
}

[[gnu::always_inline]] inline StartLanes GatherStarts(std::span<const BodyAtStart> starts,
                                                      const uint32_t (&slots)[kLanes]) {
    const BodyAtStart* records[kLanes];
    for (int l = 0; l < kLanes; ++l) records[l] = &starts[slots[l]];
    Lanes low[8];
    Lanes high[8];
    GatherFrom(records, 0, low);   // position, friction, velocity, restitution
    GatherFrom(records, 4, high);  // velocity, restitution, angular velocity, padding
    return {{low[0], low[1], low[2]},
            low[3],
            {low[4], low[5], low[6]},
            low[7],
            {high[4], high[5], high[6]}};
}

// The lanes of AxisMass (contact_setup.h), operation for operation.
[[gnu::always_inline]] inline Lanes AxisMassLanes(const BodyLanes& a, const BodyLanes& b,
                                                  const Lanes3& rA, const Lanes3& rB,
                                                  const Lanes3& direction) {
    const Lanes3 armA = Cross(rA, direction);
    const Lanes3 armB = Cross(rB, direction);
    const Lanes k =
        a.invMass + b.invMass + Dot(armA, a.invInertia * armA) + Dot(armB, b.invInertia * armB);
    const Lanes zero = Splat(0.0f);
    return Select(k > zero, Splat(1.0f) / Select(k > zero, k, Splat(1.0f)), zero);
}

// The lanes of glm's determinant of a 3x3 matrix, operation for operation.
[[gnu::always_inline]] inline Lanes Determinant(const Lanes33& m) {
    const auto at = [&](int c, int r) -> const Lanes& {
        const Lanes3& column = m.column[c];
        return r == 0 ? column.x : r == 1 ? column.y : column.z;
    };
    return +at(0, 0) * (at(1, 1) * at(2, 2) - at(2, 1) * at(1, 2)) -
           at(1, 0) * (at(0, 1) * at(2, 2) - at(2, 1) * at(0, 2)) +
           at(2, 0) * (at(0, 1) * at(1, 2) - at(1, 1) * at(0, 2));
}

// The lanes of glm's inverse of a 3x3 matrix, operation for operation.
[[gnu::always_inline]] inline Lanes33 Inverse(const Lanes33& m) {
    const auto at = [&](int c, int r) -> const Lanes& {
        const Lanes3& column = m.column[c];
        return r == 0 ? column.x : r == 1 ? column.y : column.z;
    };
    const Lanes d = Splat(1.0f) / Determinant(m);
    Lanes33 out;
    out.column[0].x = +(at(1, 1) * at(2, 2) - at(2, 1) * at(1, 2)) * d;
    out.column[1].x = -(at(1, 0) * at(2, 2) - at(2, 0) * at(1, 2)) * d;
    out.column[2].x = +(at(1, 0) * at(2, 1) - at(2, 0) * at(1, 1)) * d;
    out.column[0].y = -(at(0, 1) * at(2, 2) - at(2, 1) * at(0, 2)) * d;
    out.column[1].y = +(at(0, 0) * at(2, 2) - at(2, 0) * at(0, 2)) * d;
    out.column[2].y = -(at(0, 0) * at(2, 1) - at(2, 0) * at(0, 1)) * d;
    out.column[0].z = +(at(0, 1) * at(1, 2) - at(1, 1) * at(0, 2)) * d;
    out.column[1].z = -(at(0, 0) * at(1, 2) - at(1, 0) * at(0, 2)) * d;
    out.column[2].z = +(at(0, 0) * at(1, 1) - at(1, 0) * at(0, 1)) * d;
    return out;
}

}  // namespace

void SetUpRow(ContactRow& row, RollingLanes& rolling, std::span<const Contact> contacts,
              std::span<const BodyAtStart> starts, std::span<const SolverBody> solverBodies,
              const SolverSettings& settings) {
    const Lanes zero = Splat(0.0f);
    const Lanes one = Splat(1.0f);
    const Lanes3 none = {zero, zero, zero};
    LaneMask active;
    for (int l = 0; l < kLanes; ++l) active[l] = (row.activeLanes >> l & 1u) != 0 ? -1 : 0;
    // An inactive lane reads an active lane's contact: real numbers, then discarded.
    const uint32_t stand = row.contact[__builtin_ctz(row.activeLanes)];
    const Contact* records[kLanes];
    for (int l = 0; l < kLanes; ++l) {
        records[l] = &contacts[(row.activeLanes >> l & 1u) != 0 ? row.contact[l] : stand];
    }
    const ContactLanes c = GatherContacts(records);
    const StartLanes a = GatherStarts(starts, row.slotA);
    const StartLanes b = GatherStarts(starts, row.slotB);
    const BodyLanes sa = Gather(solverBodies, row.slotA);
    const BodyLanes sb = Gather(solverBodies, row.slotB);

    const Lanes3 anchorA = c.point - a.position;
    const Lanes3 anchorB = c.point - b.position;
    // OrthonormalBasis (orthonormal_basis.h).
    const Lanes sign = CopySign(one, c.normal.z);
    const Lanes basis = Splat(-1.0f) / (sign + c.normal.z);
    const Lanes cross = c.normal.x * c.normal.y * basis;
    const Lanes3 tangent1 = {one + sign * c.normal.x * c.normal.x * basis, sign * cross,
                             -sign * c.normal.x};
    const Lanes3 tangent2 = {cross, sign + c.normal.y * c.normal.y * basis, -c.normal.y};

    row.normal = Select3(active, c.normal, none);
    row.tangent1 = Select3(active, tangent1, none);
    row.tangent2 = Select3(active, tangent2, none);
    row.anchorA = Select3(active, anchorA, none);
    row.anchorB = Select3(active, anchorB, none);
    row.normalMass = Select(active, AxisMassLanes(sa, sb, anchorA, anchorB, c.normal), zero);
    row.tangentMass1 = Select(active, AxisMassLanes(sa, sb, anchorA, anchorB, tangent1), zero);
    row.tangentMass2 = Select(active, AxisMassLanes(sa, sb, anchorA, anchorB, tangent2), zero);
    row.normalImpulse = Select(active, c.normalImpulse, zero);
    row.tangentImpulse1 = Select(active, c.tangentImpulse1, zero);
    row.tangentImpulse2 = Select(active, c.tangentImpulse2, zero);
    row.friction = Select(active, Sqrt(a.friction * b.friction), zero);
    const Lanes dt = Splat(settings.dt);
    row.allowedApproach = Select(active & (c.separation > zero), c.separation / dt, zero);
    row.overlap = Select(active, -c.separation - Splat(settings.linearSlop), zero);
    row.pseudoImpulse = zero;
    // Restitution: the approach speed at the start of the step, before gravity.
    const Lanes3 startRelative = b.velocity + Cross(b.angularVelocity, anchorB) - a.velocity -
                                 Cross(a.angularVelocity, anchorA);
    const Lanes approach = -Dot(startRelative, c.normal);
    const LaneMask approaches = active & (approach > Splat(settings.restitutionThreshold));
    const Lanes3 gravity = {Splat(settings.gravity.x), Splat(settings.gravity.y),
                            Splat(settings.gravity.z)};
    const Lanes gravitySpeed = Abs(Dot(gravity, c.normal)) * dt;
    const Lanes restitution = Select(a.restitution < b.restitution, b.restitution, a.restitution);
    const Lanes bounce = restitution * approach - gravitySpeed;
    row.bounce = Select(approaches, Select(bounce < zero, zero, bounce), zero);

    row.rolling = false;
    const LaneMask rolls = active & (c.rollingLimit > zero);
    if (!AnyLane(rolls)) return;
    const Lanes33 inverse = sa.invInertia + sb.invInertia;
    const LaneMask turns = rolls & (Determinant(inverse) > zero);  // else neither body can turn
    if (!AnyLane(turns)) return;
    const Lanes33 mass = Inverse(inverse);
    row.rolling = true;
    rolling.limit = Select(turns, c.rollingLimit, zero);
    rolling.impulse = {zero, zero, zero};
    for (int i = 0; i < 3; ++i) rolling.mass.column[i] = Select3(turns, mass.column[i], none);
}

}  // namespace rtrt::physics
