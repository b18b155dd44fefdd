#pragma once
// ParallelFor's CUDA side (parallel_for.h): body(i) for i in [begin, end), one thread per index,
// on a stream. For .cu files.
#include <cuda_runtime.h>

#include <cstdint>

#include "engine/core/cuda_check.h"

namespace rtrt {

// 32-bit indices: the ranges are element counts of device arrays, and 64-bit index arithmetic
// would cost every thread.
template <typename Body>
__global__ void ParallelForKernel(uint32_t begin, uint32_t end, Body body) {
    const uint32_t i = begin + blockIdx.x * blockDim.x + threadIdx.x;
    if (i < end) body(i);
}

template <typename Body>
void ParallelForCuda(uint32_t begin, uint32_t end, const Body& body, cudaStream_t stream = 0) {
    constexpr uint32_t kBlock = 256;
    if (end <= begin) return;
    const uint32_t blocks = (end - begin + kBlock - 1) / kBlock;
    ParallelForKernel<<<blocks, kBlock, 0, stream>>>(begin, end, body);
    RT_CUDA_CHECK_LAUNCH();
}

}  // namespace rtrt
