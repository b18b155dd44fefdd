// The accuracy variants on the GPU: the trace kernel of cuda_renderer.cu instantiated per
// variant for the benchmark's feature set only, timed with CUDA events like `rtrt bench gpu`.
#include "bench/accuracy/accuracy_dispatch.h"
#include "bench/accuracy/accuracy_renderer.h"
#include "engine/core/device_buffer.h"
#include "engine/render_rt/cuda/device_scene.h"
#include "engine/render_rt/pixel_kernel.h"

namespace rtrt {
namespace {

template <class Policy>
__global__ void __launch_bounds__(64)
    AccuracyTraceKernel(RenderSceneView scene, uint32_t sample, uint32_t perSide, vec3* out,
                        unsigned long long* rayCount) {
    const uint32_t x = blockIdx.x * blockDim.x + threadIdx.x;
    const uint32_t y = blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= scene.width || y >= scene.height) return;
    uint32_t rays = 0;
    const vec3 value = RawSample<kAccuracyFeatures, Policy>(scene, ViewMode::kShaded, x, y, sample,
                                                            perSide, &rays);
    AccumulateSample(out[size_t(y) * scene.width + x], value, sample, perSide * perSide);
    if (rayCount) atomicAdd(rayCount, (unsigned long long)rays);
}

template <class Policy>
__global__ void __launch_bounds__(64) AccuracyObjectKernel(RenderSceneView scene, uint32_t* out) {
    const uint32_t x = blockIdx.x * blockDim.x + threadIdx.x;
    const uint32_t y = blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= scene.width || y >= scene.height) return;
    SceneHit hit;
    const Ray ray = PrimaryRay(scene.camera, x, y, scene.width, scene.height);
    const bool found = IntersectScene<Policy>(scene.tlas, ray, &hit);
    out[size_t(y) * scene.width + x] = found ? hit.instance + 1 : 0;
}

}  // namespace

CudaAccuracyRun RunAccuracyCuda(const RenderScene& scene, const RenderSettings& settings,
                                uint32_t accuracy, int warmup, int frames) {
    std::string why;
    if (!CudaBackendAvailable(&why)) throw std::runtime_error(why);
    DeviceScene device(scene);
    const RenderSceneView view = device.View(scene, settings);
    const size_t pixels = size_t(settings.width) * settings.height;
    DeviceBuffer<vec3> frame;
    frame.Resize(pixels);
    DeviceBuffer<uint32_t> objects;
    objects.Resize(pixels);
    DeviceBuffer<unsigned long long> rayCount;
    rayCount.Resize(1);
    const dim3 block(8, 8);
    const dim3 grid((settings.width + block.x - 1) / block.x,
                    (settings.height + block.y - 1) / block.y);
    cudaEvent_t start, stop;
    RT_CUDA_CHECK(cudaEventCreate(&start));
    RT_CUDA_CHECK(cudaEventCreate(&stop));
    CudaAccuracyRun run;
    DispatchAccuracy(accuracy, [&](auto tag) {
        using Policy = AccuracyPolicy<decltype(tag)::value>;
        for (int i = 0; i < warmup + frames; ++i) {
            const bool count = i == 0;  // the atomic ray count runs once, outside the timed frames
            RT_CUDA_CHECK(cudaMemset(rayCount.Data(), 0, sizeof(unsigned long long)));
            RT_CUDA_CHECK(cudaEventRecord(start));
            // One launch per sample, as the renderer's kernel (pixel_kernel.h).
            const uint32_t perSide = SamplesPerSide(view, ViewMode::kShaded);
            for (uint32_t s = 0; s < perSide * perSide; ++s) {
                AccuracyTraceKernel<Policy><<<grid, block>>>(view, s, perSide, frame.Data(),
                                                             count ? rayCount.Data() : nullptr);
                RT_CUDA_CHECK_LAUNCH();
            }
            RT_CUDA_CHECK(cudaEventRecord(stop));
            RT_CUDA_CHECK(cudaEventSynchronize(stop));
            float ms = 0.0f;
            RT_CUDA_CHECK(cudaEventElapsedTime(&ms, start, stop));
            if (i >= warmup) run.traceMs.push_back(ms);
            if (count) {
                unsigned long long rays = 0;
                rayCount.Download(std::span<unsigned long long>(&rays, 1));
                run.rays = rays;
            }
        }
        AccuracyObjectKernel<Policy><<<grid, block>>>(view, objects.Data());
        RT_CUDA_CHECK_LAUNCH();
    });
    RT_CUDA_CHECK(cudaDeviceSynchronize());
    RT_CUDA_CHECK(cudaEventDestroy(start));
    RT_CUDA_CHECK(cudaEventDestroy(stop));
    run.image = Image(settings.width, settings.height);
    frame.Download(run.image.pixels);
    run.objects.resize(pixels);
    objects.Download(run.objects);
    return run;
}

}  // namespace rtrt
