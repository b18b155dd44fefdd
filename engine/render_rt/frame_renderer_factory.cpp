// MakeFrameRenderer (frame_renderer.h), apart from the interface so that the back ends, which
// include the interface, are not included back by it.
#include "engine/render_rt/cpu/cpu_frame_renderer.h"
#include "engine/render_rt/cuda/cuda_frame_renderer.h"
#include "engine/render_rt/frame_renderer.h"

namespace rtrt {

std::unique_ptr<FrameRenderer> MakeFrameRenderer(Backend backend, const RenderScene& scene,
                                                 TlasPolicy policy) {
    if (backend == Backend::kCuda) return MakeCudaFrameRenderer(scene, policy);
    return MakeCpuFrameRenderer(scene, policy);
}

}  // namespace rtrt
