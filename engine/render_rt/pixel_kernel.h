#pragma once
// One pixel of one view, as both back ends compute it, and the dispatch from a runtime feature
// mask to the compile-time specialisation.
#include <type_traits>

#include "engine/render_rt/pixel_sample.h"
#include "engine/render_rt/trace.h"

namespace rtrt {

// The raw value a view stores before the host finishes the image (FinishView): shaded colour,
// the normal, the primary hit distance, or the heatmap's traversal counts (nodes, primitives).
// The shaded view averages samplesPerPixel stratified samples (pixel_sample.h); the others, and
// one sample, trace the ray through the pixel centre. One TraceRay call site, so that the GPU
// kernel inlines the trace once.
template <uint32_t kFeatures, uint32_t kAccuracy = kAccuracyDefault>
RT_HD inline vec3 RawPixel(const RenderSceneView& scene, ViewMode view, uint32_t x, uint32_t y,
                           uint32_t* rays) {
    const uint32_t n = view == ViewMode::kShaded ? StrataPerSide(scene.samplesPerPixel) : 1u;
    PixelResult r{};
    vec3 sum(0.0f);
    for (uint32_t s = 0; s < n * n; ++s) {
        const vec2 at = PixelSample(x, y, s, n);
        const Ray ray =
            PrimaryRay(scene.camera, float(x) + at.x, float(y) + at.y, scene.width, scene.height);
        r = TraceRay<kFeatures, kAccuracy>(scene, ray, view == ViewMode::kHeatmap);
        *rays += r.rays;
        sum += r.color;
    }
    switch (view) {
        case ViewMode::kNormals:
            return r.normal;
        case ViewMode::kDepth:
            return vec3(r.depth);
        case ViewMode::kHeatmap:
            return vec3(float(r.stats.nodesVisited), float(r.stats.primsTested), 0.0f);
        default:
            return sum / float(n * n);
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
