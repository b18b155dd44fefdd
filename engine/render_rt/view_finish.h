#pragma once
// Raw view values -> a displayable image: normals to colours, depth to grey, heatmap counts to
// the colour scale with a legend. Shaded images pass through.
#include "engine/render_rt/image.h"
#include "engine/render_rt/scene_features.h"

namespace rtrt {

struct HeatmapScale {
    float maxSteps = 0.0f;  // the value at the top of the colour scale
};
Image FinishView(const Image& raw, ViewMode view, HeatmapScale* heatmap = nullptr);

}  // namespace rtrt
