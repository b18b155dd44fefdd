#pragma once
// `rtrt bench gpu`'s measure: the CUDA trace kernel alone, timed with CUDA events.
#include <vector>

#include "engine/render_rt/render_scene.h"
#include "engine/render_rt/render_settings.h"

namespace rtrt {

// The scene is uploaded once, then `warmup` untimed and `frames` timed launches trace into a
// device framebuffer. Returns the per-frame times (ms); throws std::runtime_error when the CUDA
// back end is unavailable.
std::vector<double> TimeCudaTrace(const RenderScene& scene, const RenderSettings& settings,
                                  int warmup, int frames, RenderStats* stats = nullptr);

// Device memory in use on the current GPU (total less free, cudaMemGetInfo); false without one.
bool DeviceMemoryInUse(size_t* bytes);

}  // namespace rtrt
