#pragma once
// Setting up a row of contacts (contact_rows.h) for the passes: SetUpContact (contact_setup.h) on
// eight contacts at once.
#include <span>

#include "engine/physics_anim/contact_row.h"
#include "engine/physics_anim/solver_types.h"

namespace rtrt::physics {

// Sets up the active lanes of a row whose slots and contacts are dealt (at least one lane is
// active; inactive lanes read an active lane's bodies) from the bodies at the start of the passes,
// indexed by slot. Each lane gets SetUpContact's operations in the same order, so the same bits
// (contact_rows_test compares them); inactive lanes get zeros.
void SetUpRow(ContactRow& row, RollingLanes& rolling, std::span<const Contact> contacts,
              std::span<const BodyAtStart> starts, std::span<const SolverBody> solverBodies,
              const SolverSettings& settings);

}  // namespace rtrt::physics
