#pragma once
// Launching the trace kernel from other CUDA host code (frame loops, benchmarks).
#include <cuda_runtime.h>

#include "engine/render_rt/render_scene_view.h"
#include "engine/render_rt/split/frame_split.h"

namespace rtrt {

// Traces view (all pointers in device memory) into frame (width x height, device memory) with the
// kernel specialised for `features`, the rows of `rows` only (default: all); rayCount, if not
// null, accumulates the rays traced.
void LaunchTrace(const RenderSceneView& view, ViewMode mode, uint32_t features, vec3* frame,
                 unsigned long long* rayCount, cudaStream_t stream = 0,
                 RowBand rows = {0, UINT32_MAX});

}  // namespace rtrt
