#pragma once
#include <string>
#include <vector>

#include "engine/render_rt/image.h"
#include "engine/render_rt/render_scene.h"

namespace rtrt {

enum class Backend { kCpu, kCuda };

struct RenderSettings {
    uint32_t width = 1280;
    uint32_t height = 720;
    uint32_t maxDepth = 4;
    ViewMode view = ViewMode::kShaded;
    uint32_t enabledFeatures = kAllFeatures;  // a feature runs only if the scene has it too
    uint32_t samplesPerPixel = 1;  // shaded view; a square (1, 4, 9...), see pixel_sample.h
};

struct RenderStats {
    uint64_t rays = 0;  // primary, shadow and secondary rays traced
};

// Traces one frame on the CPU (TBB over 16x16 tiles) into target, resized to the settings' size
// (a frame loop reuses it, so no frame pays for a fresh allocation); the same image on every run.
void RenderInto(const RenderScene& scene, const RenderSettings& settings, Image& target,
                RenderStats* stats = nullptr);
inline Image RenderRaw(const RenderScene& scene, const RenderSettings& settings,
                       RenderStats* stats = nullptr) {
    Image image;
    RenderInto(scene, settings, image, stats);
    return image;
}

// Raw view values -> a displayable image: normals to colours, depth to grey, heatmap counts to
// the colour scale with a legend. Shaded images pass through.
struct HeatmapScale {
    float maxSteps = 0.0f;  // the value at the top of the colour scale
};
Image FinishView(const Image& raw, ViewMode view, HeatmapScale* heatmap = nullptr);

// Whether the CUDA back end can run here; if not, why (for the CLI's message).
bool CudaBackendAvailable(std::string* why);
// Traces one frame on the GPU; throws std::runtime_error if the CUDA back end is unavailable.
Image RenderRawCuda(const RenderScene& scene, const RenderSettings& settings,
                    RenderStats* stats = nullptr);

// Times the CUDA trace kernel alone with CUDA events: the scene is uploaded once, then `warmup`
// untimed and `frames` timed launches into a device framebuffer. Returns the per-frame times (ms).
std::vector<double> TimeCudaTrace(const RenderScene& scene, const RenderSettings& settings,
                                  int warmup, int frames, RenderStats* stats = nullptr);

inline Image Render(const RenderScene& scene, const RenderSettings& settings, Backend backend) {
    Image raw =
        backend == Backend::kCuda ? RenderRawCuda(scene, settings) : RenderRaw(scene, settings);
    return FinishView(raw, settings.view);
}

}  // namespace rtrt
