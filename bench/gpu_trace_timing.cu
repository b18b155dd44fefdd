#include "bench/gpu_trace_timing.h"
#include "bench/trace_timing.cuh"
#include "engine/core/device_buffer.h"
#include "engine/render_rt/cuda/cuda_trace.h"
#include "engine/render_rt/cuda/device_scene.h"
#include "engine/render_rt/cuda/trace_launch.cuh"

namespace rtrt {

std::vector<double> TimeCudaTrace(const RenderScene& scene, const RenderSettings& settings,
                                  int warmup, int frames, RenderStats* stats) {
    std::string why;
    if (!CudaBackendAvailable(&why)) throw std::runtime_error(why);
    DeviceStaticScene device(scene);
    const RenderSceneView view = device.View(scene, settings);
    DeviceBuffer<vec3> frame;
    frame.Resize(size_t(settings.width) * settings.height);
    const uint32_t features =
        EffectiveFeatures(scene.Features(), settings.enabledFeatures, settings.view);
    return TimeTraceLaunches(warmup, frames, stats ? &stats->rays : nullptr,
                             [&](unsigned long long* rayCount) {
                                 LaunchTrace(view, settings.view, features, frame.Data(), rayCount);
                             });
}

bool DeviceMemoryInUse(size_t* bytes) {
    size_t free = 0, total = 0;
    if (cudaMemGetInfo(&free, &total) != cudaSuccess) return false;
    *bytes = total - free;
    return true;
}

}  // namespace rtrt
