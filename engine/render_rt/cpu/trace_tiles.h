#pragma once
// The CPU back end's frame loop, as a template over the feature set and the trace policy
// (trace_policy.h): cpu_renderer.cpp instantiates production's policy, the accuracy study
// (bench/accuracy/accuracy_cpu.cpp) its variants, so that both run the same loop.
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <atomic>

#include "engine/render_rt/image.h"
#include "engine/render_rt/pixel_kernel.h"

namespace rtrt {

// Traces every pixel of view into image (view's size), 16 x 16 tiles in parallel; returns the rays
// traced.
template <uint32_t kFeatures, class Policy = TracePolicy>
uint64_t TraceTiles(const RenderSceneView& view, ViewMode mode, Image& image) {
    constexpr uint32_t kTile = 16;
    std::atomic<uint64_t> rays{0};
    tbb::parallel_for(tbb::blocked_range2d<uint32_t>(0, view.height, kTile, 0, view.width, kTile),
                      [&](const tbb::blocked_range2d<uint32_t>& tile) {
                          uint32_t tileRays = 0;
                          for (uint32_t y = tile.rows().begin(); y != tile.rows().end(); ++y)
                              for (uint32_t x = tile.cols().begin(); x != tile.cols().end(); ++x)
                                  image.At(x, y) =
                                      RawPixel<kFeatures, Policy>(view, mode, x, y, &tileRays);
                          rays += tileRays;
                      });
    return rays.load();
}

}  // namespace rtrt
