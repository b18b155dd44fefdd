#pragma once
// Every CUDA call and launch is checked; a failure throws with the call, file and line.
#include <cuda_runtime.h>

#include <stdexcept>
#include <string>

namespace rtrt {

inline void CudaCheck(cudaError_t status, const char* call, const char* file, int line) {
    if (status == cudaSuccess) return;
    throw std::runtime_error(std::string("CUDA error ") + cudaGetErrorName(status) + " (" +
                             cudaGetErrorString(status) + ") in " + call + " at " + file + ":" +
                             std::to_string(line));
}

}  // namespace rtrt

#define RT_CUDA_CHECK(call) ::rtrt::CudaCheck((call), #call, __FILE__, __LINE__)
#define RT_CUDA_CHECK_LAUNCH() RT_CUDA_CHECK(cudaGetLastError())
