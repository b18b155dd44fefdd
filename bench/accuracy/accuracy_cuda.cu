// The accuracy variants on the GPU: production's trace kernel, launch and timing loop
// (engine/render_rt/cuda/trace_launch.cuh) instantiated per variant policy, for the benchmark's
// feature set in the traversal form the scene's instance count selects, as the renderer does.
#include "bench/accuracy/accuracy_dispatch.h"
#include "bench/accuracy/accuracy_renderer.h"
#include "bench/trace_timing.cuh"
#include "engine/render_rt/cuda/device_scene.h"
#include "engine/render_rt/cuda/trace_launch.cuh"

namespace rtrt {
namespace {

template <uint32_t kFeatures, class Policy>
__global__ void __launch_bounds__(64) AccuracyObjectKernel(RenderSceneView scene, uint32_t* out) {
    const uint32_t x = blockIdx.x * blockDim.x + threadIdx.x;
    const uint32_t y = blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= scene.width || y >= scene.height) return;
    SceneHit hit;
    const Ray ray = PrimaryRay(scene.camera, x, y, scene.width, scene.height);
    const bool found = TraceIntersect<kFeatures, Policy>(scene.tlas, ray, &hit, nullptr);
    out[size_t(y) * scene.width + x] = found ? hit.instance + 1 : 0;
}

}  // namespace

CudaAccuracyRun RunAccuracyCuda(const RenderScene& scene, const RenderSettings& settings,
                                uint32_t accuracy, int warmup, int frames) {
    std::string why;
    if (!CudaBackendAvailable(&why)) throw std::runtime_error(why);
    DeviceStaticScene device(scene);
    const RenderSceneView view = device.View(scene, settings);
    const size_t pixels = size_t(settings.width) * settings.height;
    DeviceBuffer<vec3> frame;
    frame.Resize(pixels);
    DeviceBuffer<uint32_t> objects;
    objects.Resize(pixels);
    const dim3 block(8, 8);
    const dim3 grid((settings.width + block.x - 1) / block.x,
                    (settings.height + block.y - 1) / block.y);
    const bool manyInstances = (scene.Features() & kFeatureManyInstances) != 0;
    CudaAccuracyRun run;
    DispatchAccuracy(accuracy, [&](auto tag) {
        using Policy = AccuracyPolicy<decltype(tag)::value>;
        auto measure = [&](auto featureTag) {
            constexpr uint32_t kFeatures = decltype(featureTag)::value;
            run.traceMs = TimeTraceLaunches(warmup, frames, &run.rays, [&](unsigned long long* n) {
                LaunchTraceKernel<kFeatures, Policy>(view, ViewMode::kShaded, frame.Data(), n);
            });
            AccuracyObjectKernel<kFeatures, Policy><<<grid, block>>>(view, objects.Data());
            RT_CUDA_CHECK_LAUNCH();
        };
        if (manyInstances)
            measure(std::integral_constant<uint32_t, kAccuracyFeatures | kFeatureManyInstances>{});
        else
            measure(std::integral_constant<uint32_t, kAccuracyFeatures>{});
    });
    RT_CUDA_CHECK(cudaDeviceSynchronize());
    run.image = Image(settings.width, settings.height);
    frame.Download(run.image.pixels);
    run.objects.resize(pixels);
    objects.Download(run.objects);
    return run;
}

}  // namespace rtrt
