#pragma once
// The CPU back end's trace of a view in host memory: TBB over 16x16 tiles, the RT_HD pixel body
// specialised for the scene's features.
#include "engine/render_rt/image.h"
#include "engine/render_rt/render_scene_view.h"
#include "engine/render_rt/render_settings.h"

namespace rtrt {

// Traces `view` (whose sceneFeatures the scene calls for) into target, resized to the settings'
// size; the same image on every run.
void TraceViewCpu(const RenderSceneView& view, uint32_t sceneFeatures,
                  const RenderSettings& settings, Image& target, RenderStats* stats);

}  // namespace rtrt
