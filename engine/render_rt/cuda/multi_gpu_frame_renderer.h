#pragma once
// Split-frame rendering over several GPUs of one host. Every GPU holds the whole scene (BLASes,
// materials and textures replicated) and its TLAS, built there from the same instance records or
// copied from the display GPU's (GpuSplit::Tlas); each traces a band of rows, the bands following
// the GPUs' last trace times (split/frame_split.h), and the bands are gathered into the display
// GPU's framebuffer, peer to peer where the GPUs allow it. Pixels do not depend on the GPU that
// traces them, so the image is the single-GPU image bit for bit. CUDA code only.
#include <memory>

#include "engine/render_rt/frame_renderer.h"

namespace rtrt {

// Over gpus.devices (two or more; the first is the display GPU). Throws std::runtime_error for
// more than FrameTimes::kMaxGpus.
std::unique_ptr<FrameRenderer> MakeMultiGpuFrameRenderer(const RenderScene& scene,
                                                         TlasPolicy policy,
                                                         BlasRebuildPolicy blasPolicy,
                                                         const GpuSplit& gpus);

}  // namespace rtrt
