#pragma once
// Sequential impulses over the step's contacts (Catto 2005, "Iterative Dynamics with Temporal
// Coherence"): warm starting, Coulomb friction, rolling resistance, speculative contacts,
// restitution, and split-impulse position correction. The arithmetic is in contact_rows.cpp and
// contact_row_setup.cpp.
#include <cstdint>
#include <span>
#include <vector>

#include "engine/physics_anim/contact_coloring.h"
#include "engine/physics_anim/contact_rows.h"
#include "engine/physics_anim/sim_body.h"
#include "engine/physics_anim/solver_types.h"
#include "engine/physics_anim/stage_runner.h"

namespace rtrt::physics {

// The solver's view of a body at the start of the contact passes, written to its slot in out and
// starts, with its pseudo velocity there at zero. The caller orders the slots by place, so that
// the bodies that one thread solves (a run of regions, see ContactBatches) lie together in memory
// and share no cache line with another thread's.
inline void GatherSolverBody(const SimBody& s, uint32_t slot, std::span<SolverBody> out,
                             std::span<BodyAtStart> starts, std::span<PseudoVelocity> pseudo) {
    pseudo[slot] = PseudoVelocity{};
    starts[slot] = {s.position, s.friction, s.startVelocity, s.restitution, s.startAngularVelocity};
    SolverBody& b = out[slot];
    b.velocity = s.velocity;
    b.angularVelocity = s.angularVelocity;
    b.invMass = s.awake ? s.invMass : 0.0f;
    b.invInertia = s.awake ? s.invInertiaWorld : glm::mat3(0.0f);
}

// What SolveContacts keeps between steps, so that a step allocates nothing.
struct ContactSolverScratch {
    // A run of colours solved in one stage: one colour cut into shares and blocks, or several
    // small ones (or the overflow) in order, in one block.
    struct Span {
        uint32_t firstColor;
        uint32_t lastColor;
    };
    struct Stage {
        RowPass pass;
        bool writeBack;  // the last pass that changes impulses: they go back to the contacts
        uint32_t span;
    };
    struct Block {
        uint32_t rowBegin;
        uint32_t rowEnd;
    };
    std::vector<Span> spans;
    std::vector<uint32_t> firstBlock;  // per span and share, into blockRows; then the total
    std::vector<Block> blockRows;
    std::vector<Stage> stages;
    std::vector<uint32_t> blocks;  // per stage and share
    ContactRows rows;              // what the passes read and write
    StageRunner runner;
};

// The contact passes of a step, each colour by colour (the manifolds of a colour at once, eight
// at a time in ContactRows' lanes, on every thread TBB lends; only awake bodies are written, so
// the result does not depend on the number of threads):
// 1. Warm start: the contacts' seeded impulses are applied, so that the iterations start from
//    the last step's solution and resting stacks converge in a few iterations instead of
//    sinking.
// 2. velocityIterations of rolling resistance, friction within the Coulomb cone and a
//    non-negative normal impulse that lets a speculative contact (separation > 0) close its gap
//    within the step but not overshoot it.
// 3. Restitution, one pass (as Box2D v3 does): a touching contact whose approach speed u exceeds
//    the threshold leaves at e * u - |g . n| * dt. Dropping one step's worth of gravity from the
//    rebound means that a bounce never gains energy (a ball that reached the contact at the
//    start of the step would otherwise also keep the speed gravity gave it during the step).
// 4. positionIterations of split impulse: pseudo velocities push overlapping bodies apart by
//    positionCorrection of the overlap beyond linearSlop per step; they move the bodies but are
//    discarded afterwards, so the correction adds no kinetic energy (unlike Baumgarte
//    stabilisation of the velocities). They touch nothing that 1 to 3 touch, so they run in the
//    same stages as the first velocity iterations, with the same result.
// The contacts' impulses are replaced by the solved ones. solverBodies, starts and pseudo are
// indexed by slot (slotOfBody).
void SolveContacts(std::span<const uint32_t> slotOfBody, std::span<const BodyAtStart> starts,
                   std::span<SolverBody> solverBodies, std::span<PseudoVelocity> pseudo,
                   std::span<Contact> contacts, const ContactBatches& batches,
                   const SolverSettings& settings, ContactSolverScratch& scratch);

}  // namespace rtrt::physics
