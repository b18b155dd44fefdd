#include "engine/physics_anim/contact_solver.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <cmath>

#include "engine/core/parallel_for.h"
#include "engine/physics_anim/procedural_motion.h"

namespace rtrt::physics {

namespace {

ContactAxis MakeAxis(const SolverBody& a, const SolverBody& b, vec3 rA, vec3 rB, vec3 direction) {
    ContactAxis axis;
    axis.direction = direction;
    axis.armA = glm::cross(rA, direction);
    axis.armB = glm::cross(rB, direction);
    const float k = a.invMass + b.invMass + glm::dot(axis.armA, a.invInertia * axis.armA) +
                    glm::dot(axis.armB, b.invInertia * axis.armB);
    axis.mass = k > 0.0f ? 1.0f / k : 0.0f;
    return axis;
}

float Speed(const SolverBody& a, const SolverBody& b, const ContactAxis& axis) {
    return glm::dot(axis.direction, b.velocity - a.velocity) +
           glm::dot(b.angularVelocity, axis.armB) - glm::dot(a.angularVelocity, axis.armA);
}

// Applies the impulse `linear` (a vector) with angular lever sums armA and armB: b gains it, a
// loses it. A body that is not awake (zero inverse mass) is not written: other manifolds of the
// same colour may read it at the same time.
void Push(SolverBody& a, SolverBody& b, vec3 linear, vec3 armA, vec3 armB) {
    if (a.invMass > 0.0f) {
        a.velocity -= a.invMass * linear;
        a.angularVelocity -= a.invInertia * armA;
    }
    if (b.invMass > 0.0f) {
        b.velocity += b.invMass * linear;
        b.angularVelocity += b.invInertia * armB;
    }
}

void PushAlong(SolverBody& a, SolverBody& b, const ContactAxis& axis, float impulse) {
    Push(a, b, impulse * axis.direction, impulse * axis.armA, impulse * axis.armB);
}

// Below this many manifolds a step is solved on one thread: the threads' start costs more.
constexpr uint32_t kParallelManifolds = 1024;
// The smallest slice of a colour that a thread claims at once.
constexpr uint32_t kMinBlockManifolds = 32;
// Blocks per share: what is left for the other threads to take when one is behind.
constexpr uint32_t kBlocksPerShare = 4;

}  // namespace

void GatherSolverBodies(std::span<const SimBody> bodies, std::span<const uint32_t> slotOfBody,
                        std::span<SolverBody> out) {
    ParallelFor(0, bodies.size(), 1024, [&](size_t i) {
        const SimBody& s = bodies[i];
        SolverBody& b = out[slotOfBody[i]];
        b.velocity = s.velocity;
        b.angularVelocity = s.angularVelocity;
        b.invMass = s.awake ? s.invMass : 0.0f;
        b.invInertia = s.awake ? s.invInertiaWorld : glm::mat3(0.0f);
    });
}

void PrepareContacts(std::span<const SimBody> bodies, std::span<const uint32_t> slotOfBody,
                     std::span<const SolverBody> solverBodies, std::span<Contact> contacts,
                     const SolverSettings& settings) {
    ParallelFor(0, contacts.size(), 512, [&](size_t k) {
        Contact& c = contacts[k];
        const SimBody& a = bodies[c.a];
        const SimBody& b = bodies[c.b];
        c.slotA = slotOfBody[c.a];
        c.slotB = slotOfBody[c.b];
        const SolverBody& sa = solverBodies[c.slotA];
        const SolverBody& sb = solverBodies[c.slotB];
        const vec3 rA = c.point - a.position;
        const vec3 rB = c.point - b.position;
        c.anchorA = rA;
        c.anchorB = rB;
        vec3 t1;
        vec3 t2;
        OrthonormalBasis(c.normal, t1, t2);
        c.normalAxis = MakeAxis(sa, sb, rA, rB, c.normal);
        c.tangentAxis1 = MakeAxis(sa, sb, rA, rB, t1);
        c.tangentAxis2 = MakeAxis(sa, sb, rA, rB, t2);
        c.normalImpulse = 0.0f;
        c.tangentImpulse1 = 0.0f;
        c.tangentImpulse2 = 0.0f;
        c.pseudoImpulse = 0.0f;
        c.rollingImpulse = vec3(0.0f);
        c.rollingMass = glm::mat3(0.0f);
        if (c.rollingLimit > 0.0f) {
            const glm::mat3 inverse = sa.invInertia + sb.invInertia;
            if (glm::determinant(inverse) > 0.0f) {
                c.rollingMass = glm::inverse(inverse);
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

namespace {

void WarmStartContact(std::span<SolverBody> bodies, const Contact& c) {
    const ContactAxis& n = c.normalAxis;
    const ContactAxis& t1 = c.tangentAxis1;
    const ContactAxis& t2 = c.tangentAxis2;
    Push(bodies[c.slotA], bodies[c.slotB],
         c.normalImpulse * n.direction + c.tangentImpulse1 * t1.direction +
             c.tangentImpulse2 * t2.direction,
         c.normalImpulse * n.armA + c.tangentImpulse1 * t1.armA + c.tangentImpulse2 * t2.armA,
         c.normalImpulse * n.armB + c.tangentImpulse1 * t1.armB + c.tangentImpulse2 * t2.armB);
}

void RestituteContact(std::span<SolverBody> bodies, Contact& c, const SolverSettings& settings) {
    if (c.normalImpulse <= 0.0f || c.approachSpeed <= settings.restitutionThreshold) return;
    const float target = c.restitution * c.approachSpeed - c.gravitySpeed;
    if (target <= 0.0f) return;
    SolverBody& a = bodies[c.slotA];
    SolverBody& b = bodies[c.slotB];
    const float vn = Speed(a, b, c.normalAxis);
    const float impulse = std::max(c.normalImpulse - c.normalAxis.mass * (vn - target), 0.0f);
    PushAlong(a, b, c.normalAxis, impulse - c.normalImpulse);
    c.normalImpulse = impulse;
}

enum class Pass : uint8_t { kWarmStart, kVelocity, kVelocityAndPosition, kRestitution, kPosition };

}  // namespace

void SolveContacts(std::span<SolverBody> bodies, std::span<PseudoVelocity> pseudo,
                   std::span<Contact> contacts, const ContactBatches& batches,
                   const SolverSettings& settings, ContactSolverScratch& scratch) {
    const uint32_t colors = batches.Colors();
    if (colors == 0) return;
    // A stage is one pass over one colour. Each colour is cut into one share per thread, by
    // region when the batches have regions (else evenly), and each share into blocks. The
    // overflow colour is a single block, solved in order by one thread.
    const float invDt = 1.0f / settings.dt;
    ContactRows& rows = scratch.rows;
    rows.Build(contacts, batches, invDt, settings.linearSlop);
    const int threads =
        batches.Manifolds() < kParallelManifolds ? 1 : StageRunner::AvailableThreads();
    const auto shareCount = static_cast<uint32_t>(threads);
    scratch.shares.clear();
    for (uint32_t color = 0; color < colors; ++color) {
        const uint32_t colorBegin = batches.colorBegin[color];
        const uint32_t colorEnd = batches.colorBegin[color + 1];
        const uint32_t manifolds = colorEnd - colorBegin;
        if (batches.lastIsOverflow && color + 1 == colors) {
            scratch.shares.push_back({colorBegin, colorEnd, std::max(1u, manifolds)});
            for (uint32_t s = 1; s < shareCount; ++s) {
                scratch.shares.push_back({colorEnd, colorEnd, 1});
            }
            continue;
        }
        // Shares and blocks start at the rows' groups.
        constexpr uint32_t kGroup = ContactRows::kGroupManifolds;
        const uint32_t blockSize =
            (std::max(kMinBlockManifolds, manifolds / (kBlocksPerShare * shareCount)) + kGroup -
             1) /
            kGroup * kGroup;
        for (uint32_t s = 0; s < shareCount; ++s) {
            uint32_t begin =
                colorBegin + static_cast<uint32_t>(uint64_t{manifolds} * s / shareCount);
            uint32_t end =
                colorBegin + static_cast<uint32_t>(uint64_t{manifolds} * (s + 1) / shareCount);
            if (batches.regions > 0) {
                begin = batches.RegionBegin(color, s * batches.regions / shareCount);
                end = batches.RegionBegin(color, (s + 1) * batches.regions / shareCount);
            }
            scratch.shares.push_back(
                {rows.GroupStart(color, begin), rows.GroupStart(color, end), blockSize});
        }
    }
    scratch.stages.clear();
    scratch.blocks.clear();
    const auto addPass = [&](Pass pass, bool writeBack = false) {
        for (uint32_t color = 0; color < colors; ++color) {
            scratch.stages.push_back({static_cast<uint8_t>(pass), writeBack, color});
            for (uint32_t s = 0; s < shareCount; ++s) {
                const ContactSolverScratch::Share& share = scratch.shares[color * shareCount + s];
                scratch.blocks.push_back((share.end - share.begin + share.blockSize - 1) /
                                         share.blockSize);
            }
        }
    };
    // The position iterations read and write only pseudo velocities, which nothing else touches,
    // so they ride along with the first velocity iterations: the same arithmetic in fewer stages,
    // each contact read once for both.
    const int shared = std::min(settings.velocityIterations, settings.positionIterations);
    addPass(Pass::kWarmStart);
    for (int i = 0; i < shared; ++i) {
        addPass(Pass::kVelocityAndPosition, i + 1 == settings.velocityIterations);
    }
    for (int i = shared; i < settings.velocityIterations; ++i) {
        addPass(Pass::kVelocity, i + 1 == settings.velocityIterations);
    }
    addPass(Pass::kRestitution);
    for (int i = shared; i < settings.positionIterations; ++i) addPass(Pass::kPosition);

    const float rate = settings.positionCorrection / settings.dt;
    scratch.runner.Run(scratch.blocks, threads, [&](size_t stageIndex, uint32_t s, uint32_t block) {
        const ContactSolverScratch::Stage& stage = scratch.stages[stageIndex];
        const ContactSolverScratch::Share& share = scratch.shares[stage.color * shareCount + s];
        const uint32_t first = share.begin + block * share.blockSize;
        const uint32_t last = std::min(share.end, first + share.blockSize);
        const uint32_t begin = batches.manifoldBegin[first];
        const uint32_t end = batches.manifoldBegin[last];
        const auto solveRows = [&](RowPass pass) {
            const uint32_t rowBegin = rows.RowBegin(stage.color, first);
            const uint32_t rowEnd = rows.RowBegin(stage.color, last);
            rows.Solve(bodies, pseudo, rowBegin, rowEnd, pass, rate);
            if (stage.writeBack) rows.WriteBack(contacts, rowBegin, rowEnd);
        };
        switch (static_cast<Pass>(stage.pass)) {
            case Pass::kWarmStart:
                for (uint32_t k = begin; k < end; ++k) WarmStartContact(bodies, contacts[k]);
                break;
            case Pass::kVelocity:
                solveRows(RowPass::kVelocity);
                break;
            case Pass::kVelocityAndPosition:
                solveRows(RowPass::kVelocityAndPosition);
                break;
            case Pass::kRestitution:
                for (uint32_t k = begin; k < end; ++k)
                    RestituteContact(bodies, contacts[k], settings);
                break;
            case Pass::kPosition:
                solveRows(RowPass::kPosition);
                break;
        }
    });
}

}  // namespace rtrt::physics
