#pragma once
// One pixel of one view, as both back ends compute it, and the dispatch from a runtime feature
// mask to the compile-time specialisation.
#include <type_traits>

#include "engine/render_rt/pixel_sample.h"
#include "engine/render_rt/trace.h"

namespace rtrt {

// How many samples per side a pixel of a view takes: n x n stratified samples (pixel_sample.h) in
// the shaded view, the pixel centre alone in the others.
RT_HD inline uint32_t SamplesPerSide(const RenderSceneView& scene, ViewMode view) {
    return view == ViewMode::kShaded ? StrataPerSide(scene.samplesPerPixel) : 1u;
}

// The raw value a view stores for sample s of a pixel's n x n, before the host finishes the image
// (FinishView): shaded colour, the normal, the primary hit distance, or the heatmap's traversal
// counts (nodes, primitives).
template <uint32_t kFeatures, class Policy = TracePolicy>
RT_HD inline vec3 RawSample(const RenderSceneView& scene, ViewMode view, uint32_t x, uint32_t y,
                            uint32_t s, uint32_t n, uint32_t* rays) {
    const vec2 at = PixelSample(x, y, s, n);
    const Ray ray =
        PrimaryRay(scene.camera, float(x) + at.x, float(y) + at.y, scene.width, scene.height);
    const PixelResult r = TraceRay<kFeatures, Policy>(scene, ray, view == ViewMode::kHeatmap);
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

// Adds sample s of count to a pixel: the samples summed in order, divided once after the last.
// The CPU loops over the samples (RawPixel); the GPU launches its kernel once per sample, so that
// no loop surrounds the inlined trace: around it, the kernels of few instances (uncapped
// registers) lost 14-22% on the paper scene. Both do the same float operations.
RT_HD inline void AccumulateSample(vec3& pixel, vec3 sample, uint32_t s, uint32_t count) {
    pixel = s == 0 ? sample : pixel + sample;
    if (count > 1 && s + 1 == count) pixel /= float(count);
}

template <uint32_t kFeatures, class Policy = TracePolicy>
RT_HD inline vec3 RawPixel(const RenderSceneView& scene, ViewMode view, uint32_t x, uint32_t y,
                           uint32_t* rays) {
    const uint32_t n = SamplesPerSide(scene, view);
    vec3 pixel(0.0f);
    for (uint32_t s = 0; s < n * n; ++s)
        AccumulateSample(pixel, RawSample<kFeatures, Policy>(scene, view, x, y, s, n, rays), s,
                         n * n);
    return pixel;
}

// Views other than shaded need only the primary hit: their specialisation has no secondary rays.
// The traversal form's bit is kept (the frame renderer's choice may clear it afterwards).
inline uint32_t EffectiveFeatures(uint32_t sceneFeatures, uint32_t enabled, ViewMode view) {
    const uint32_t shape = sceneFeatures & kFeatureManyInstances;
    if (view != ViewMode::kShaded) return shape;
    uint32_t features = (sceneFeatures & enabled & kAllFeatures) | shape;
    // PBR kernels always sample textures (IsKernelFeatureSet); with textures turned off, PBR
    // materials fall back to their Blinn-Phong approximation.
    if ((features & kFeatureTextures) == 0) features &= ~kFeaturePbr;
    return features;
}

// The feature sets that have a kernel: PBR only with textures, which halves PBR's instantiations.
constexpr bool IsKernelFeatureSet(uint32_t features) {
    return (features & kFeaturePbr) == 0 || (features & kFeatureTextures) != 0;
}

// Calls fn with std::integral_constant<uint32_t, features>: one instantiation per combination.
template <uint32_t kCandidate = 0, typename Fn>
decltype(auto) DispatchFeatures(uint32_t features, Fn&& fn) {
    if constexpr (kCandidate == kAllFeatureBits) {
        return fn(std::integral_constant<uint32_t, kCandidate>{});
    } else {
        if constexpr (IsKernelFeatureSet(kCandidate)) {
            if ((features & kAllFeatureBits) == kCandidate)
                return fn(std::integral_constant<uint32_t, kCandidate>{});
        }
        return DispatchFeatures<kCandidate + 1>(features, std::forward<Fn>(fn));
    }
}

}  // namespace rtrt
