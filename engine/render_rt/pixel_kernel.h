#pragma once
// One pixel of one view, as both back ends compute it, and the dispatch from a runtime feature
// mask to the compile-time specialisation.
#include <type_traits>

#include "engine/render_rt/trace.h"

namespace rtrt {

// The raw value a view stores before the host finishes the image (FinishView): shaded colour,
// the normal, the primary hit distance, or the heatmap's traversal counts (nodes, primitives).
template <uint32_t kFeatures>
RT_HD inline vec3 RawPixel(const RenderSceneView& scene, ViewMode view, uint32_t x, uint32_t y,
                           uint32_t* rays) {
    const PixelResult r = TracePixel<kFeatures>(scene, x, y, view == ViewMode::kHeatmap);
    *rays += r.rays;
    switch (view) {
        case ViewMode::kNormals:
            return r.normal;
        case ViewMode::kDepth:
            return vec3(r.depth);
        case ViewMode::kHeatmap:
            return vec3(float(r.stats.nodesVisited), float(r.stats.primsTested), 0.0f);
        default:
            return r.color;
    }
}

// Views other than shaded need only the primary hit: their specialisation has no secondary rays.
// The traversal form stays as the scene chose it.
inline uint32_t EffectiveFeatures(uint32_t sceneFeatures, uint32_t enabled, ViewMode view) {
    const uint32_t shape = sceneFeatures & kFeatureManyInstances;
    if (view != ViewMode::kShaded) return shape;
    return (sceneFeatures & enabled & kAllFeatures) | shape;
}

// Calls fn with std::integral_constant<uint32_t, features>: one instantiation per combination.
template <uint32_t kCandidate = 0, typename Fn>
decltype(auto) DispatchFeatures(uint32_t features, Fn&& fn) {
    if constexpr (kCandidate == kAllFeatureBits) {
        return fn(std::integral_constant<uint32_t, kCandidate>{});
    } else {
        if ((features & kAllFeatureBits) == kCandidate)
            return fn(std::integral_constant<uint32_t, kCandidate>{});
        return DispatchFeatures<kCandidate + 1>(features, std::forward<Fn>(fn));
    }
}

}  // namespace rtrt
