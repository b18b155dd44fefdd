#pragma once
// The instance-grid benchmark of the CUDA issue, defined so that other renderers can run it: N
// instances of dragon res4 (scaled to largest extent 1, centred) on a cube grid of side
// s = ceil(cbrt(N)) with spacing 1.5 centred on the origin; instance i sits at cell
// (i mod s, (i / s) mod s, i / s^2), rotates about +y by (time + 0.37 i) and is offset in x by
// 0.2 sin(time + i); time advances 0.016 per frame; camera at (0, 0, 3.2 h + 2) with h = 0.75 s,
// otherwise the paper scene's view, material, light and depth. The TLAS is rebuilt every frame;
// a refit of the same tree over the same boxes is timed beside it (not part of the frame).
#include <memory>
#include <vector>

#include "engine/bvh/blas/blas.h"

namespace rtrt {

struct InstanceGridRow {
    uint32_t instances = 0;
    double updateMs = 0, tlasMs = 0, refitMs = 0, traceMs = 0, totalMs = 0;  // medians, CUDA events
    uint64_t rays = 0;
    double bytesPerInstance = 0;  // instance record + TLAS arrays on the GPU
};

// Runs `frames` timed frames (after 20 warm-up frames) per instance count on the GPU.
std::vector<InstanceGridRow> RunInstanceGridBench(std::shared_ptr<const Blas> model,
                                                  const std::vector<uint32_t>& counts, int frames);

}  // namespace rtrt
