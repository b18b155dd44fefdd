#pragma once
// The CPU back end of a running scene: it owns the host TLAS (an LBVH refit or rebuilt by
// DynamicTlas) and traces with TBB. Made by MakeFrameRenderer.
#include <memory>

#include "engine/render_rt/frame_renderer.h"

namespace rtrt {

std::unique_ptr<FrameRenderer> MakeCpuFrameRenderer(const RenderScene& scene, TlasPolicy policy,
                                                    BlasRebuildPolicy blasPolicy);

}  // namespace rtrt
