#pragma once
// The contact passes' layout of a step's contacts: rows of eight contacts, one per lane, solved at
// once (lanes.h). The manifolds of one colour share no moving body, so eight of them can be solved
// side by side and give exactly what solving them one after another gives: each lane does one
// contact's arithmetic on bodies no other lane writes.
//
// A colour's manifolds are taken in groups of kGroupManifolds, in layout order. A group's
// manifolds are dealt to the lanes, the ones with most contacts first, each to the lane with the
// fewest contacts so far, and a lane walks through its manifolds' contacts in order, one per row:
// a manifold's contacts are solved in their own order, as before, and a group of spheres (one
// contact) and boxes (up to eight) fills most lanes of most rows. The overflow colour, whose
// manifolds may share bodies, has groups of one manifold: one lane per row, in order.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "engine/physics_anim/contact_coloring.h"
#include "engine/physics_anim/contact_row.h"
#include "engine/physics_anim/lanes.h"
#include "engine/physics_anim/solver_types.h"

namespace rtrt::physics {

// A pass over rows (contact_solver.h describes them). The position iterations touch only pseudo
// velocities, so one pass may do a velocity and a position iteration.
enum class RowPass : uint8_t {
    kWarmStart,
    kVelocity,
    kVelocityAndPosition,
    kRestitution,
    kPosition
};

class ContactRows {
  public:
    static constexpr uint32_t kGroupManifolds = 4 * kLanes;

    // Lays out the contacts of batches, with their effective masses and targets from the bodies
    // at the start of the passes (starts and solverBodies, indexed by slotOfBody): Plan, then
    // Fill of every row.
    void Build(std::span<const Contact> contacts, std::span<const uint32_t> slotOfBody,
               std::span<const BodyAtStart> starts, std::span<const SolverBody> solverBodies,
               const ContactBatches& batches, const SolverSettings& settings);
    // Deals the contacts to rows (how many, and which lane holds which contact), without filling
    // them. The arguments must outlive the Fill calls that follow.
    void Plan(std::span<const Contact> contacts, std::span<const uint32_t> slotOfBody,
              std::span<const BodyAtStart> starts, std::span<const SolverBody> solverBodies,
              const ContactBatches& batches, const SolverSettings& settings);
    // Fills rows [begin, end), which start and end at groups (RowBegin's): the solver fills a
    // block's rows in its first pass, on the thread that then solves them, so that they are
    // written where they are read instead of in another core's cache.
    void Fill(uint32_t begin, uint32_t end);

    // The first row of manifold in colour color, which must be a group boundary of that colour
    // (GroupStart) or its end: rows [RowBegin(c, m0), RowBegin(c, m1)) hold manifolds [m0, m1).
    uint32_t RowBegin(uint32_t color, uint32_t manifold) const;
    // The first group boundary at or after manifold in colour color (its end if none).
    uint32_t GroupStart(uint32_t color, uint32_t manifold) const;

    // One pass over rows [begin, end), bodies and pseudo velocities indexed by slot;
    // positionRate: the share of the overlap that the pseudo velocities remove per second.
    void Solve(std::span<SolverBody> bodies, std::span<PseudoVelocity> pseudo, uint32_t begin,
               uint32_t end, RowPass pass, float positionRate);
    // Copies the impulses of rows [begin, end) back to their contacts.
    void WriteBack(std::span<Contact> contacts, uint32_t begin, uint32_t end) const;

    uint32_t Rows() const { return static_cast<uint32_t>(rows_.size()); }
    const ContactRow& Row(uint32_t r) const { return rows_[r]; }
    // Row r's rolling resistance, when Row(r).rolling.
    const RollingLanes& Rolling(uint32_t r) const { return rolling_[r]; }

  private:
    template <RowPass kPass>
    void SolveRows(std::span<SolverBody> bodies, std::span<PseudoVelocity> pseudo, uint32_t begin,
                   uint32_t end, float positionRate);
    uint32_t GroupSize(uint32_t color) const;
    // The manifolds [first, last) of a group.
    std::pair<uint32_t, uint32_t> GroupManifolds(uint32_t group) const;
    // Deals group g's manifolds to lanes: lane of each manifold in laneOf, returns the rows.
    uint32_t Deal(uint32_t group, std::span<uint8_t> laneOf) const;

    void FillGroup(uint32_t group);

    // Plan's inputs, for Fill.
    std::span<const Contact> contacts_;
    std::span<const uint32_t> slotOfBody_;
    std::span<const BodyAtStart> starts_;
    std::span<const SolverBody> solverBodies_;
    const SolverSettings* settings_ = nullptr;
    const ContactBatches* batches_ = nullptr;
    std::vector<uint32_t> colorGroupBegin_;  // per colour, and the total at the end
    std::vector<uint32_t> groupColor_;
    std::vector<uint32_t> groupRowBegin_;  // per group, and the total at the end
    std::vector<uint8_t> laneOf_;          // per group, each manifold's lane (Deal's)
    std::vector<ContactRow> rows_;
    std::vector<RollingLanes> rolling_;  // per row
};

}  // namespace rtrt::physics
