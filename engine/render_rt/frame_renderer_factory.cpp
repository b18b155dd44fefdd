// MakeFrameRenderer (frame_renderer.h), apart from the interface so that the back ends, which
// include the interface, are not included back by it.
#include "engine/render_rt/cpu/cpu_frame_renderer.h"
#include "engine/render_rt/cuda/cuda_frame_renderer.h"
#include "engine/render_rt/frame_renderer.h"

namespace rtrt {

std::unique_ptr<FrameRenderer> MakeFrameRenderer(Backend backend, const RenderScene& scene,
                                                 TlasPolicy policy, BlasRebuildPolicy blasPolicy,
                                                 const GpuSplit& gpus) {
    if (backend == Backend::kCuda) return MakeCudaFrameRenderer(scene, policy, blasPolicy, gpus);
    return MakeCpuFrameRenderer(scene, policy, blasPolicy);
}

}  // namespace rtrt
