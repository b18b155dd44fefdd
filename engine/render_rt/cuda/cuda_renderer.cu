// The CUDA back end: the trace kernel of trace_launch.cuh (the RT_HD body of pixel_kernel.h, one
// thread per pixel) with production's policy, specialised per scene feature set.
#include <string>

#include "engine/core/cuda_unavailable.h"
#include "engine/core/device_buffer.h"
#include "engine/render_rt/cuda/cuda_trace.h"
#include "engine/render_rt/cuda/device_scene.h"
#include "engine/render_rt/cuda/trace_launch.cuh"
#include "engine/render_rt/renderer.h"

namespace rtrt {

void LaunchTrace(const RenderSceneView& view, ViewMode mode, uint32_t features, vec3* frame,
                 unsigned long long* rayCount, cudaStream_t stream, RowBand rows) {
    DispatchFeatures(features, [&](auto featureTag) {
        LaunchTraceKernel<decltype(featureTag)::value>(view, mode, frame, rayCount, stream, rows);
    });
}

bool CudaBackendAvailable(std::string* why) {
    int count = 0;
    const cudaError_t status = cudaGetDeviceCount(&count);
    if (status != cudaSuccess || count == 0) {
        if (why) *why = "no CUDA device is usable here (" + NoCudaDeviceReason(status) + ")";
        return false;
    }
    return true;
}

uint32_t CudaDeviceCount() {
    int count = 0;
    return cudaGetDeviceCount(&count) == cudaSuccess ? uint32_t(count) : 0u;
}

Image RenderRawCuda(const RenderScene& scene, const RenderSettings& settings, RenderStats* stats) {
    std::string why;
    if (!CudaBackendAvailable(&why)) throw std::runtime_error(why + "; use the CPU back end");
    DeviceStaticScene device(scene);
    const RenderSceneView view = device.View(scene, settings);
    DeviceBuffer<unsigned long long> rayCount;
    if (stats) {
        rayCount.Resize(1);
        RT_CUDA_CHECK(cudaMemset(rayCount.Data(), 0, sizeof(unsigned long long)));
    }
    DeviceBuffer<vec3> frame;
    frame.Resize(size_t(settings.width) * settings.height);
    // One frame: nothing to measure the traversal forms on, so kAuto takes the nested form.
    const uint32_t features = WithTraversalForm(
        EffectiveFeatures(scene.Features(), settings.enabledFeatures, settings.view),
        settings.traversal);
    LaunchTrace(view, settings.view, features, frame.Data(), rayCount.Data());
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
