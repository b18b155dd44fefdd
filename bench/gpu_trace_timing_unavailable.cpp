// Built when nvcc is absent.
#include <stdexcept>

#include "bench/gpu_trace_timing.h"

namespace rtrt {

std::vector<double> TimeCudaTrace(const RenderScene&, const RenderSettings&, int, int,
                                  RenderStats*) {
    throw std::runtime_error("the CUDA back end is not built into this rtrt");
}

bool DeviceMemoryInUse(size_t*) { return false; }

}  // namespace rtrt
