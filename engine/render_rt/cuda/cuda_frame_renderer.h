#pragma once
// The CUDA back end of a running scene (rtrt play, rtrt bench frame, the window). The BLASes,
// materials and lights go up once; each frame sends only the instance records that changed,
// brings the TLAS up to date on the GPU (an LBVH rebuilt when instances were added or removed
// and, under the runtime's TlasPolicy, whenever records changed; a policy may refit instead) and
// traces into a device framebuffer. Made by MakeFrameRenderer.
#include <memory>

#include "engine/render_rt/frame_renderer.h"

namespace rtrt {

// On one GPU, or split over several (multi_gpu_frame_renderer.h). Throws std::runtime_error when
// the CUDA back end is unavailable, saying why.
std::unique_ptr<FrameRenderer> MakeCudaFrameRenderer(const RenderScene& scene, TlasPolicy policy,
                                                     BlasRebuildPolicy blasPolicy,
                                                     const GpuSplit& gpus = {});

}  // namespace rtrt
