// Built when nvcc is absent: the instance-grid benchmark needs the GPU.
#include <stdexcept>

#include "bench/instance_grid_bench.h"

namespace rtrt {

std::vector<InstanceGridRow> RunInstanceGridBench(std::shared_ptr<const Blas>,
                                                  const std::vector<uint32_t>&, int) {
    throw std::runtime_error("the instance-grid benchmark needs rtrt built with CUDA");
}

}  // namespace rtrt
