#pragma once
// Compile-time scene features: each combination is its own kernel instantiation, so a scene
// without refraction runs code without refraction (Falcor's StaticParams, pbrt's "only launch
// what the scene has").
#include <cstdint>

namespace rtrt {

enum SceneFeature : uint32_t {
    kFeatureShadows = 1u << 0,
    kFeatureReflection = 1u << 1,
    kFeatureRefraction = 1u << 2,
};
inline constexpr uint32_t kAllFeatures = kFeatureShadows | kFeatureReflection | kFeatureRefraction;

// What a pixel stores.
enum class ViewMode : uint32_t { kShaded = 0, kNormals = 1, kDepth = 2, kHeatmap = 3 };

}  // namespace rtrt
