// A build without CUDA: the GPU contact solver's interface, and no device.
#include "engine/physics_anim/gpu_contact_solver.h"

namespace rtrt::physics {

std::unique_ptr<GpuContactSolver> GpuContactSolver::Create(std::string* why) {
    if (why) *why = "this build of rtrt has no CUDA back end";
    return nullptr;
}

}  // namespace rtrt::physics
