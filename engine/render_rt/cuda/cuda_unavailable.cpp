// Built when nvcc is absent: the CUDA back end reports why it cannot run.
#include <stdexcept>

#include "engine/render_rt/cuda/cuda_frame_renderer.h"
#include "engine/render_rt/renderer.h"

namespace rtrt {

bool CudaBackendAvailable(std::string* why) {
    if (why) *why = "this rtrt was built without CUDA (nvcc was not found at configure time)";
    return false;
}

uint32_t CudaDeviceCount() { return 0; }

Image RenderRawCuda(const RenderScene&, const RenderSettings&, RenderStats*) {
    throw std::runtime_error("the CUDA back end is not built into this rtrt; use the CPU back end");
}

std::unique_ptr<FrameRenderer> MakeCudaFrameRenderer(const RenderScene&, TlasPolicy,
                                                     BlasRebuildPolicy, const GpuSplit&) {
    throw std::runtime_error("the CUDA back end is not built into this rtrt; use the CPU back end");
}

}  // namespace rtrt
