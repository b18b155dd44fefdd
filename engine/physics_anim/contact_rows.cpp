#include "engine/physics_anim/contact_rows.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <iterator>
#include <utility>

#include "engine/core/parallel_for.h"
#include "engine/physics_anim/body_lanes.h"
#include "engine/physics_anim/contact_row_setup.h"

namespace rtrt::physics {

namespace {

// The velocity of b's point of contact relative to a's.
[[gnu::always_inline]] inline Lanes3 RelativeVelocity(const BodyLanes& a, const BodyLanes& b,
                                                      const ContactRow& row) {
    return b.velocity + Cross(b.angularVelocity, row.anchorB) - a.velocity -
           Cross(a.angularVelocity, row.anchorA);
}

// b gains the impulse at the contact point, a loses it. A body that does not move has zero
// inverse mass and inertia, so its lanes keep their values exactly.
[[gnu::always_inline]] inline void Push(BodyLanes& a, BodyLanes& b, const ContactRow& row,
                                        const Lanes3& impulse) {
    a.velocity = a.velocity - a.invMass * impulse;
    a.angularVelocity = a.angularVelocity - a.invInertia * Cross(row.anchorA, impulse);
    b.velocity = b.velocity + b.invMass * impulse;
    b.angularVelocity = b.angularVelocity + b.invInertia * Cross(row.anchorB, impulse);
}

// Rolling resistance, friction and the normal impulse of one row, on the bodies' lanes.
[[gnu::always_inline]] inline void SolveVelocity(BodyLanes& a, BodyLanes& b, ContactRow& row,
                                                 RollingLanes* rolling) {
    const Lanes zero = Splat(0.0f);
    const Lanes one = Splat(1.0f);
    if (rolling != nullptr) {
        const LaneMask on = (rolling->limit > zero) & (row.normalImpulse > zero);
        const Lanes3 spin = b.angularVelocity - a.angularVelocity;
        Lanes3 impulse = rolling->impulse - rolling->mass * spin;
        const Lanes maxRolling = rolling->limit * row.normalImpulse;
        const Lanes length = Sqrt(Dot(impulse, impulse));
        impulse = Select(length > maxRolling, maxRolling / length, one) * impulse;
        const Lanes3 delta = Select3(on, impulse - rolling->impulse, Lanes3{zero, zero, zero});
        rolling->impulse = Select3(on, impulse, rolling->impulse);
        a.angularVelocity = a.angularVelocity - a.invInertia * delta;
        b.angularVelocity = b.angularVelocity + b.invInertia * delta;
    }
    // Friction before the normal, so that the normal constraint, which matters more, is solved
    // last.
    const Lanes maxFriction = row.friction * row.normalImpulse;
    const LaneMask rubs = maxFriction > zero;
    if (AnyLane(rubs)) {
        const Lanes3 dv = RelativeVelocity(a, b, row);
        Lanes t1 = row.tangentImpulse1 - row.tangentMass1 * Dot(row.tangent1, dv);
        Lanes t2 = row.tangentImpulse2 - row.tangentMass2 * Dot(row.tangent2, dv);
        const Lanes length = Sqrt(t1 * t1 + t2 * t2);
        const Lanes clamp = Select(length > maxFriction, maxFriction / length, one);
        t1 = t1 * clamp;
        t2 = t2 * clamp;
        const Lanes d1 = Select(rubs, t1 - row.tangentImpulse1, zero);
        const Lanes d2 = Select(rubs, t2 - row.tangentImpulse2, zero);
        Push(a, b, row, d1 * row.tangent1 + d2 * row.tangent2);
        row.tangentImpulse1 = Select(rubs, t1, row.tangentImpulse1);
        row.tangentImpulse2 = Select(rubs, t2, row.tangentImpulse2);
    }
    const Lanes vn = Dot(row.normal, RelativeVelocity(a, b, row));
    const Lanes impulse =
        Max(row.normalImpulse - row.normalMass * (vn + row.allowedApproach), zero);
    Push(a, b, row, (impulse - row.normalImpulse) * row.normal);
    row.normalImpulse = impulse;
}

// One split-impulse iteration of a row: pushes overlapping bodies apart through their pseudo
// velocities, by rate of the overlap per second. Rows without overlap beyond the slop (most of
// them) read no pseudo velocities.
[[gnu::always_inline]] inline void SolvePosition(std::span<PseudoVelocity> pseudo,
                                                 const BodyLanes& a, const BodyLanes& b,
                                                 ContactRow& row, float rate) {
    const Lanes zero = Splat(0.0f);
    const LaneMask overlaps = row.overlap > zero;
    if (!AnyLane(overlaps)) return;
    PseudoLanes pa = GatherPseudo(pseudo, row.slotA);
    PseudoLanes pb = GatherPseudo(pseudo, row.slotB);
    const Lanes vn = Dot(row.normal, pb.linear + Cross(pb.angular, row.anchorB) - pa.linear -
                                         Cross(pa.angular, row.anchorA));
    const Lanes impulse =
        Max(row.pseudoImpulse - row.normalMass * (vn - Splat(rate) * row.overlap), zero);
    const Lanes3 push = Select(overlaps, impulse - row.pseudoImpulse, zero) * row.normal;
    row.pseudoImpulse = Select(overlaps, impulse, row.pseudoImpulse);
    pa.linear = pa.linear - a.invMass * push;
    pa.angular = pa.angular - a.invInertia * Cross(row.anchorA, push);
    pb.linear = pb.linear + b.invMass * push;
    pb.angular = pb.angular + b.invInertia * Cross(row.anchorB, push);
    ScatterPseudo(pseudo, row.slotA, row.activeLanes, a.invMass, pa);
    ScatterPseudo(pseudo, row.slotB, row.activeLanes, b.invMass, pb);
}

// Applies the seeded impulses.
[[gnu::always_inline]] inline void WarmStart(BodyLanes& a, BodyLanes& b, const ContactRow& row) {
    Push(a, b, row,
         row.normalImpulse * row.normal + row.tangentImpulse1 * row.tangent1 +
             row.tangentImpulse2 * row.tangent2);
}

// The lanes whose contact bounces: it touches (pushes) and approached faster than the threshold.
[[gnu::always_inline]] inline LaneMask Bounces(const ContactRow& row) {
    const Lanes zero = Splat(0.0f);
    return (row.bounce > zero) & (row.normalImpulse > zero);
}

// A touching contact that approached faster than the threshold leaves at its bounce speed.
[[gnu::always_inline]] inline void Restitute(BodyLanes& a, BodyLanes& b, ContactRow& row) {
    const Lanes zero = Splat(0.0f);
    const LaneMask bounces = Bounces(row);
    if (!AnyLane(bounces)) return;
    const Lanes vn = Dot(row.normal, RelativeVelocity(a, b, row));
    const Lanes impulse = Max(row.normalImpulse - row.normalMass * (vn - row.bounce), zero);
    Push(a, b, row, Select(bounces, impulse - row.normalImpulse, zero) * row.normal);
    row.normalImpulse = Select(bounces, impulse, row.normalImpulse);
}

}  // namespace

uint32_t ContactRows::GroupSize(uint32_t color) const {
    return batches_->lastIsOverflow && color + 1 == batches_->Colors() ? 1u : kGroupManifolds;
}

uint32_t ContactRows::GroupStart(uint32_t color, uint32_t manifold) const {
    const uint32_t begin = batches_->colorBegin[color];
    const uint32_t end = batches_->colorBegin[color + 1];
    const uint32_t size = GroupSize(color);
    if (manifold <= begin) return begin;
    return std::min(end, begin + (manifold - begin + size - 1) / size * size);
}

uint32_t ContactRows::RowBegin(uint32_t color, uint32_t manifold) const {
    const uint32_t begin = batches_->colorBegin[color];
    if (manifold >= batches_->colorBegin[color + 1]) {
        return groupRowBegin_[colorGroupBegin_[color + 1]];
    }
    return groupRowBegin_[colorGroupBegin_[color] + (manifold - begin) / GroupSize(color)];
}

std::pair<uint32_t, uint32_t> ContactRows::GroupManifolds(uint32_t group) const {
    const uint32_t color = groupColor_[group];
    const uint32_t size = GroupSize(color);
    const uint32_t first = batches_->colorBegin[color] + (group - colorGroupBegin_[color]) * size;
    return {first, std::min(batches_->colorBegin[color + 1], first + size)};
}

uint32_t ContactRows::Deal(uint32_t group, std::span<uint8_t> laneOf) const {
    const auto [first, last] = GroupManifolds(group);
    const auto points = [&](uint32_t m) {
        return batches_->manifoldBegin[m + 1] - batches_->manifoldBegin[m];
    };
    // Most contacts first, in layout order among equals: a stable insertion sort, as a group is
    // small (std::stable_sort would allocate a buffer per group).
    std::array<uint32_t, kGroupManifolds> order;
    for (uint32_t m = first; m < last; ++m) {
        uint32_t at = m - first;
        for (; at > 0 && points(order[at - 1]) < points(m); --at) order[at] = order[at - 1];
        order[at] = m;
    }
    std::array<uint32_t, kLanes> load{};
    for (uint32_t i = 0; i < last - first; ++i) {
        const auto lane =
            static_cast<uint8_t>(std::min_element(load.begin(), load.end()) - load.begin());
        laneOf[order[i] - first] = lane;
        load[lane] += points(order[i]);
    }
    return *std::max_element(load.begin(), load.end());
}

void ContactRows::Build(std::span<const Contact> contacts, std::span<const uint32_t> slotOfBody,
                        std::span<const BodyAtStart> starts,
                        std::span<const SolverBody> solverBodies, const ContactBatches& batches,
                        const SolverSettings& settings) {
    Plan(contacts, slotOfBody, starts, solverBodies, batches, settings);
    ParallelFor(0, colorGroupBegin_.back(), 64,
                [&](size_t g) { FillGroup(static_cast<uint32_t>(g)); });
}

void ContactRows::Plan(std::span<const Contact> contacts, std::span<const uint32_t> slotOfBody,
                       std::span<const BodyAtStart> starts,
                       std::span<const SolverBody> solverBodies, const ContactBatches& batches,
                       const SolverSettings& settings) {
    contacts_ = contacts;
    slotOfBody_ = slotOfBody;
    starts_ = starts;
    solverBodies_ = solverBodies;
    settings_ = &settings;
    batches_ = &batches;
    const uint32_t colors = batches.Colors();
    colorGroupBegin_.assign(1, 0);
    groupColor_.clear();
    for (uint32_t color = 0; color < colors; ++color) {
        const uint32_t manifolds = batches.colorBegin[color + 1] - batches.colorBegin[color];
        const uint32_t size = GroupSize(color);
        const uint32_t groups = (manifolds + size - 1) / size;
        groupColor_.insert(groupColor_.end(), groups, color);
        colorGroupBegin_.push_back(colorGroupBegin_.back() + groups);
    }
    const uint32_t groups = colorGroupBegin_.back();
    groupRowBegin_.resize(groups + 1);
    laneOf_.resize(size_t{groups} * kGroupManifolds);
    ParallelFor(0, groups, 64, [&](size_t g) {
        const std::span<uint8_t> laneOf(laneOf_.data() + g * kGroupManifolds, kGroupManifolds);
        groupRowBegin_[g + 1] = Deal(static_cast<uint32_t>(g), laneOf);
    });
    groupRowBegin_[0] = 0;
    for (uint32_t g = 0; g < groups; ++g) groupRowBegin_[g + 1] += groupRowBegin_[g];
    rows_.resize(groupRowBegin_[groups]);
    rolling_.resize(rows_.size());
}

void ContactRows::Fill(uint32_t begin, uint32_t end) {
    // Every group has a row, so a group boundary is one group's first row.
    auto group = static_cast<uint32_t>(
        std::lower_bound(groupRowBegin_.begin(), groupRowBegin_.end(), begin) -
        groupRowBegin_.begin());
    for (; groupRowBegin_[group] < end; ++group) FillGroup(group);
}

void ContactRows::FillGroup(uint32_t group) {
    const uint8_t* laneOf = laneOf_.data() + size_t{group} * kGroupManifolds;
    const auto [first, last] = GroupManifolds(group);
    const uint32_t rowBegin = groupRowBegin_[group];
    const uint32_t rowEnd = groupRowBegin_[group + 1];
    for (uint32_t r = rowBegin; r < rowEnd; ++r) {
        ContactRow& row = rows_[r];
        row.activeLanes = 0;
        std::fill(std::begin(row.contact), std::end(row.contact), 0u);
    }
    std::array<uint32_t, kLanes> next{};
    for (uint32_t m = first; m < last; ++m) {
        const uint8_t l = laneOf[m - first];
        for (uint32_t k = batches_->manifoldBegin[m]; k < batches_->manifoldBegin[m + 1]; ++k) {
            ContactRow& row = rows_[rowBegin + next[l]++];
            row.slotA[l] = slotOfBody_[contacts_[k].a];
            row.slotB[l] = slotOfBody_[contacts_[k].b];
            row.contact[l] = k;
            row.activeLanes |= 1u << l;
        }
    }
    for (uint32_t r = rowBegin; r < rowEnd; ++r) {
        ContactRow& row = rows_[r];
        // Empty lanes read the bodies of an active one: real memory, never written.
        const int active = __builtin_ctz(row.activeLanes);
        for (int l = 0; l < kLanes; ++l) {
            if ((row.activeLanes >> l & 1u) != 0) continue;
            row.slotA[l] = row.slotA[active];
            row.slotB[l] = row.slotB[active];
        }
        SetUpRow(row, rolling_[r], contacts_, starts_, solverBodies_, *settings_);
    }
}

void ContactRows::Solve(std::span<SolverBody> bodies, std::span<PseudoVelocity> pseudo,
                        uint32_t begin, uint32_t end, RowPass pass, float positionRate) {
    switch (pass) {
        case RowPass::kWarmStart:
            SolveRows<RowPass::kWarmStart>(bodies, pseudo, begin, end, positionRate);
            break;
        case RowPass::kVelocity:
            SolveRows<RowPass::kVelocity>(bodies, pseudo, begin, end, positionRate);
            break;
        case RowPass::kVelocityAndPosition:
            SolveRows<RowPass::kVelocityAndPosition>(bodies, pseudo, begin, end, positionRate);
            break;
        case RowPass::kRestitution:
            SolveRows<RowPass::kRestitution>(bodies, pseudo, begin, end, positionRate);
            break;
        case RowPass::kPosition:
            SolveRows<RowPass::kPosition>(bodies, pseudo, begin, end, positionRate);
            break;
    }
}

template <RowPass kPass>
void ContactRows::SolveRows(std::span<SolverBody> bodies, std::span<PseudoVelocity> pseudo,
                            uint32_t begin, uint32_t end, float positionRate) {
    constexpr bool kVelocity =
        kPass == RowPass::kVelocity || kPass == RowPass::kVelocityAndPosition;
    constexpr bool kPosition =
        kPass == RowPass::kPosition || kPass == RowPass::kVelocityAndPosition;
    for (uint32_t r = begin; r < end; ++r) {
        ContactRow& row = rows_[r];
        // The next row's bodies are fetched while this row is solved: its arithmetic depends on
        // its own bodies' loads, and the stores to them would hold the next row's loads back.
        if (r + 1 < end) {
            const ContactRow& next = rows_[r + 1];
            for (int l = 0; l < kLanes; ++l) {
                _mm_prefetch(reinterpret_cast<const char*>(&bodies[next.slotA[l]]), _MM_HINT_T0);
                _mm_prefetch(reinterpret_cast<const char*>(&bodies[next.slotB[l]]), _MM_HINT_T0);
            }
        }
        if constexpr (kPass == RowPass::kRestitution) {
            // Most rows have nothing to bounce: their bodies would be read and written unchanged.
            if (!AnyLane(Bounces(row))) continue;
        }
        BodyLanes a = Gather(bodies, row.slotA);
        BodyLanes b = Gather(bodies, row.slotB);
        if constexpr (kPass == RowPass::kWarmStart) WarmStart(a, b, row);
        if constexpr (kVelocity) SolveVelocity(a, b, row, row.rolling ? &rolling_[r] : nullptr);
        if constexpr (kPass == RowPass::kRestitution) Restitute(a, b, row);
        if constexpr (kPass != RowPass::kPosition) {
            Scatter(bodies, row.slotA, row.activeLanes, a);
            Scatter(bodies, row.slotB, row.activeLanes, b);
        }
        if constexpr (kPosition) SolvePosition(pseudo, a, b, row, positionRate);
    }
}

void ContactRows::WriteBack(std::span<Contact> contacts, uint32_t begin, uint32_t end) const {
    for (uint32_t r = begin; r < end; ++r) {
        const ContactRow& row = rows_[r];
        for (int l = 0; l < kLanes; ++l) {
            if ((row.activeLanes >> l & 1u) == 0) continue;
            Contact& c = contacts[row.contact[l]];
            c.normalImpulse = row.normalImpulse[l];
            c.tangentImpulse1 = row.tangentImpulse1[l];
            c.tangentImpulse2 = row.tangentImpulse2[l];
        }
    }
}

}  // namespace rtrt::physics
