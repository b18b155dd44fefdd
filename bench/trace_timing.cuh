#pragma once
// The benchmarks' timing loop for trace launches (bench gpu, the accuracy study's GPU runs).
#include <cuda_runtime.h>

#include <cstdint>
#include <span>
#include <vector>

#include "engine/core/cuda_check.h"
#include "engine/core/device_buffer.h"

namespace rtrt {

// Times `warmup` untimed and `frames` timed calls of launch(rayCount) with CUDA events and returns
// the timed ones in ms. The atomic ray count runs once, in the first call, outside the timed
// frames: that call gets a zeroed device counter, read back into *rays; the others get null.
template <typename Launch>
std::vector<double> TimeTraceLaunches(int warmup, int frames, uint64_t* rays, Launch&& launch) {
    DeviceBuffer<unsigned long long> rayCount;
    rayCount.Resize(1);
    cudaEvent_t start, stop;
    RT_CUDA_CHECK(cudaEventCreate(&start));
    RT_CUDA_CHECK(cudaEventCreate(&stop));
    std::vector<double> times;
    for (int i = 0; i < warmup + frames; ++i) {
        const bool count = i == 0;
        RT_CUDA_CHECK(cudaMemset(rayCount.Data(), 0, sizeof(unsigned long long)));
        RT_CUDA_CHECK(cudaEventRecord(start));
        launch(count ? rayCount.Data() : nullptr);
        RT_CUDA_CHECK(cudaEventRecord(stop));
        RT_CUDA_CHECK(cudaEventSynchronize(stop));
        float ms = 0.0f;
        RT_CUDA_CHECK(cudaEventElapsedTime(&ms, start, stop));
        if (i >= warmup) times.push_back(ms);
        if (count && rays) {
            unsigned long long counted = 0;
            rayCount.Download(std::span<unsigned long long>(&counted, 1));
            *rays = counted;
        }
    }
    RT_CUDA_CHECK(cudaEventDestroy(start));
    RT_CUDA_CHECK(cudaEventDestroy(stop));
    return times;
}

}  // namespace rtrt
