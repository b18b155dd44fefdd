#pragma once
// Makes a CUDA device current for a scope and restores the one that was: code that owns memory,
// streams and events on one GPU of several runs its calls under a guard, so that callers need
// not know which device is current.
#include "engine/core/cuda_check.h"

namespace rtrt {

class CudaDeviceGuard {
  public:
    explicit CudaDeviceGuard(int device) {
        RT_CUDA_CHECK(cudaGetDevice(&previous_));
        if (device != previous_) RT_CUDA_CHECK(cudaSetDevice(device));
        changed_ = device != previous_;
    }
    ~CudaDeviceGuard() {
        if (changed_) cudaSetDevice(previous_);  // a destructor does not throw
    }
    CudaDeviceGuard(const CudaDeviceGuard&) = delete;
    CudaDeviceGuard& operator=(const CudaDeviceGuard&) = delete;

  private:
    int previous_ = 0;
    bool changed_ = false;
};

}  // namespace rtrt
