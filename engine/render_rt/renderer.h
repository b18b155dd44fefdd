#pragma once
// One image of a scene as it is (its own TLAS), on either back end: `rtrt render`, reference
// images, tests. A running scene is traced by a FrameRenderer (frame_renderer.h) instead.
#include "engine/render_rt/image.h"
#include "engine/render_rt/render_scene.h"
#include "engine/render_rt/render_settings.h"
#include "engine/render_rt/view_finish.h"

namespace rtrt {

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

// Traces one frame on the GPU; throws std::runtime_error if the CUDA back end is unavailable.
Image RenderRawCuda(const RenderScene& scene, const RenderSettings& settings,
                    RenderStats* stats = nullptr);

inline Image Render(const RenderScene& scene, const RenderSettings& settings, Backend backend) {
    Image raw =
        backend == Backend::kCuda ? RenderRawCuda(scene, settings) : RenderRaw(scene, settings);
    return FinishView(raw, settings.view);
}

}  // namespace rtrt
