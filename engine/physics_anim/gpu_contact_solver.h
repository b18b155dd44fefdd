#pragma once
// The contact passes of SolveContacts (contact_solver.h) on a CUDA device: the step's contacts and
// bodies go to the GPU, one thread per manifold solves a colour's manifolds at once, one colour
// after another with a grid-wide barrier between them, and the velocities, pseudo velocities and
// impulses come back. Each manifold's contacts are solved in their order with the arithmetic of
// the CPU rows in the same order (contact_setup.h here, its lane-wise twin contact_row_setup.h
// there, which contact_rows_test holds to the same bits; no fused multiply-adds on either side),
// and the manifolds of a colour share no moving body, so the result is the CPU solver's,
// whatever the number of CPU threads. One difference: where a lane of a CPU row has nothing to
// do while others in its row work, the CPU applies a zero impulse to its bodies and the GPU
// skips it, which can turn a velocity component of -0 into +0 on the CPU alone; every other bit
// agrees. A build without CUDA has the interface and no device.
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "engine/physics_anim/contact_coloring.h"
#include "engine/physics_anim/solver_types.h"

namespace rtrt::physics {

// Where the last Solve spent its time on the device, by CUDA events (ms).
struct GpuSolverTimes {
    double uploadMs = 0.0;    // the contacts and bodies to the device
    double solveMs = 0.0;     // the set-up and every pass
    double downloadMs = 0.0;  // velocities, pseudo velocities and impulses back
};

class GpuContactSolver {
  public:
    virtual ~GpuContactSolver() = default;

    // A solver on the first CUDA device, or nullptr with why it cannot be (no CUDA in the build,
    // no device or no usable driver, a device without cooperative launches or on which the
    // kernel cannot run). Never throws.
    static std::unique_ptr<GpuContactSolver> Create(std::string* why);

    // As SolveContacts, without its CPU scratch: solverBodies' velocities, pseudo and the
    // contacts' impulses are replaced by the solved ones. Throws std::runtime_error when the
    // device fails.
    virtual void Solve(std::span<const uint32_t> slotOfBody, std::span<const BodyAtStart> starts,
                       std::span<SolverBody> solverBodies, std::span<PseudoVelocity> pseudo,
                       std::span<Contact> contacts, const ContactBatches& batches,
                       const SolverSettings& settings) = 0;
    virtual GpuSolverTimes LastTimes() const = 0;
};

}  // namespace rtrt::physics
