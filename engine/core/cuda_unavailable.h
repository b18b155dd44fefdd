#pragma once
// Why no CUDA device is usable, in words a user can act on.
#include <cuda_runtime.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace rtrt {

// The reason for cudaGetDeviceCount's STATUS (cudaSuccess: it counted none). The runtime calls a
// machine without the NVIDIA driver "insufficient driver": said so, a user would update a driver
// that is not there.
inline std::string NoCudaDeviceReason(cudaError_t status) {
    if (status == cudaSuccess) return "no CUDA device found";
    if (status == cudaErrorInsufficientDriver) {
        std::error_code ignored;
        if (!std::filesystem::exists("/proc/driver/nvidia/version", ignored))
            return "no NVIDIA driver is loaded: no NVIDIA GPU?";
        return "the NVIDIA driver is older than this CUDA " +
               std::to_string(CUDART_VERSION / 1000) + " build needs: update the driver";
    }
    return cudaGetErrorString(status);
}

}  // namespace rtrt
