#pragma once
// Launching the trace kernel from other CUDA host code (frame loops, benchmarks).
#include <cuda_runtime.h>

#include "engine/core/device_buffer.h"
#include "engine/render_rt/render_scene_view.h"
#include "engine/render_rt/split/frame_split.h"

namespace rtrt {

// A primary ray that hit, queued by the primary-hit kernel for the shading kernel (64 bytes, so
// that a thread loads it in four 16-byte loads).
struct alignas(16) QueuedPrimaryHit {
    Ray ray;
    SceneHit hit;
    uint32_t pixel;  // y * width + x
    uint32_t pad[2];
};
static_assert(sizeof(QueuedPrimaryHit) == 64);

// Device memory for the shaded view's two kernels (trace_launch.cuh): a queue entry per pixel
// and a counter per row. A band of rows [b, e) uses the entries from b * width and counter b, so
// that bands traced at once on several streams do not share either.
class TraceWorkspace {
  public:
    void Reserve(uint32_t width, uint32_t height) {
        if (queue_.Size() < size_t(width) * height) queue_.Resize(size_t(width) * height);
        if (counters_.Size() < height) counters_.Resize(height);
    }
    QueuedPrimaryHit* Queue() const { return queue_.Data(); }
    uint32_t* Counters() const { return counters_.Data(); }

  private:
    DeviceBuffer<QueuedPrimaryHit> queue_;
    DeviceBuffer<uint32_t> counters_;
};

// Experiment switch (RTRT_TWO_KERNELS=1): the callers pass their workspace.
bool TwoKernelTraceWanted();

// Traces view (all pointers in device memory) into frame (width x height, device memory) with the
// kernel specialised for `features`, the rows of `rows` only (default: all); rayCount, if not
// null, accumulates the rays traced. With a workspace (reserved for the view's size) the shaded
// view runs as two kernels, primary hits and then shading (trace_launch.cuh).
void LaunchTrace(const RenderSceneView& view, ViewMode mode, uint32_t features, vec3* frame,
                 unsigned long long* rayCount, cudaStream_t stream = 0,
                 RowBand rows = {0, UINT32_MAX}, TraceWorkspace* workspace = nullptr);

}  // namespace rtrt
