// The CUDA back end: the RT_HD body of pixel_kernel.h, one thread per pixel, specialised per
// scene feature set.
#include <vector>

#include "engine/core/device_buffer.h"
#include "engine/render_rt/cuda/cuda_trace.h"
#include "engine/render_rt/cuda/device_scene.h"
#include "engine/render_rt/pixel_kernel.h"
#include "engine/render_rt/renderer.h"

namespace rtrt {
namespace {

// Scenes of many instances trace with a register cap (blocks of 64 threads that must fit per
// SM): their time goes into long, divergent traversals that more warps in flight hide better.
// On the H100, 16 blocks (64 registers, some spilled) made the instance grid 1.6-1.8x faster than
// no cap (bench/results/gpu-register-cap-sweep-h100-2026-11-25.txt); the paper scene (few
// instances) runs fastest uncapped. cmake -DRTRT_TRACE_MIN_BLOCKS=N overrides it, for experiments.
#if !defined(RTRT_TRACE_MIN_BLOCKS)
#define RTRT_TRACE_MIN_BLOCKS 16
#endif
constexpr int TraceMinBlocks(uint32_t features) {
    return (features & kFeatureManyInstances) != 0 ? RTRT_TRACE_MIN_BLOCKS : 1;
}

template <uint32_t kFeatures>
__global__ void __launch_bounds__(64, TraceMinBlocks(kFeatures))
    TraceKernel(RenderSceneView scene, ViewMode view, uint32_t sample, uint32_t perSide, vec3* out,
                unsigned long long* rayCount) {
    const uint32_t x = blockIdx.x * blockDim.x + threadIdx.x;
    const uint32_t y = blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= scene.width || y >= scene.height) return;
    uint32_t rays = 0;
    const vec3 value = RawSample<kFeatures>(scene, view, x, y, sample, perSide, &rays);
    AccumulateSample(out[size_t(y) * scene.width + x], value, sample, perSide * perSide);
    if (rayCount) atomicAdd(rayCount, (unsigned long long)rays);
}

}  // namespace

void LaunchTrace(const RenderSceneView& view, ViewMode mode, uint32_t features, vec3* frame,
                 unsigned long long* rayCount, cudaStream_t stream) {
    const dim3 block(8, 8);
    const dim3 grid((view.width + block.x - 1) / block.x, (view.height + block.y - 1) / block.y);
    DispatchFeatures(features, [&](auto featureTag) {
        constexpr uint32_t kFeatures = decltype(featureTag)::value;
        // One launch per sample (AccumulateSample says why).
        const uint32_t perSide = SamplesPerSide(view, mode);
        for (uint32_t s = 0; s < perSide * perSide; ++s) {
            TraceKernel<kFeatures>
                <<<grid, block, 0, stream>>>(view, mode, s, perSide, frame, rayCount);
            RT_CUDA_CHECK_LAUNCH();
        }
    });
}

bool CudaBackendAvailable(std::string* why) {
    int count = 0;
    const cudaError_t status = cudaGetDeviceCount(&count);
    if (status != cudaSuccess || count == 0) {
        if (why)
            *why = std::string("no CUDA device is usable here (") +
                   (status != cudaSuccess ? cudaGetErrorString(status) : "no device found") + ")";
        return false;
    }
    return true;
}

std::vector<double> TimeCudaTrace(const RenderScene& scene, const RenderSettings& settings,
                                  int warmup, int frames, RenderStats* stats) {
    std::string why;
    if (!CudaBackendAvailable(&why)) throw std::runtime_error(why);
    DeviceStaticScene device(scene);
    const RenderSceneView view = device.View(scene, settings);
    DeviceBuffer<vec3> frame;
    frame.Resize(size_t(settings.width) * settings.height);
    DeviceBuffer<unsigned long long> rayCount;
    rayCount.Resize(1);
    const uint32_t features =
        EffectiveFeatures(scene.Features(), settings.enabledFeatures, settings.view);
    cudaEvent_t start, stop;
    RT_CUDA_CHECK(cudaEventCreate(&start));
    RT_CUDA_CHECK(cudaEventCreate(&stop));
    std::vector<double> times;
    for (int i = 0; i < warmup + frames; ++i) {
        const bool count = i == 0;  // the atomic ray count runs once, outside the timed frames
        RT_CUDA_CHECK(cudaMemset(rayCount.Data(), 0, sizeof(unsigned long long)));
        RT_CUDA_CHECK(cudaEventRecord(start));
        LaunchTrace(view, settings.view, features, frame.Data(), count ? rayCount.Data() : nullptr);
        RT_CUDA_CHECK(cudaEventRecord(stop));
        RT_CUDA_CHECK(cudaEventSynchronize(stop));
        float ms = 0.0f;
        RT_CUDA_CHECK(cudaEventElapsedTime(&ms, start, stop));
        if (i >= warmup) times.push_back(ms);
        if (count && stats) {
            unsigned long long rays = 0;
            rayCount.Download(std::span<unsigned long long>(&rays, 1));
            stats->rays = rays;
        }
    }
    RT_CUDA_CHECK(cudaEventDestroy(start));
    RT_CUDA_CHECK(cudaEventDestroy(stop));
    return times;
}

Image RenderRawCuda(const RenderScene& scene, const RenderSettings& settings, RenderStats* stats) {
    std::string why;
    if (!CudaBackendAvailable(&why)) throw std::runtime_error(why + "; use --backend cpu");
    DeviceStaticScene device(scene);
    const RenderSceneView view = device.View(scene, settings);
    DeviceBuffer<unsigned long long> rayCount;
    if (stats) {
        rayCount.Resize(1);
        RT_CUDA_CHECK(cudaMemset(rayCount.Data(), 0, sizeof(unsigned long long)));
    }
    DeviceBuffer<vec3> frame;
    frame.Resize(size_t(settings.width) * settings.height);
    LaunchTrace(view, settings.view,
                EffectiveFeatures(scene.Features(), settings.enabledFeatures, settings.view),
                frame.Data(), rayCount.Data());
    RT_CUDA_CHECK(cudaDeviceSynchronize());
    Image image(settings.width, settings.height);
    frame.Download(image.pixels);
    if (stats) {
        unsigned long long rays = 0;
        rayCount.Download(std::span<unsigned long long>(&rays, 1));
        stats->rays = rays;
    }
    return image;
}

}  // namespace rtrt
