#pragma once
// Compile-time scene features: each combination is its own kernel instantiation, so a scene
// without refraction runs code without refraction (Falcor's StaticParams, pbrt's "only launch
// what the scene has").
#include <cstddef>
#include <cstdint>

namespace rtrt {

enum SceneFeature : uint32_t {
    kFeatureShadows = 1u << 0,
    kFeatureReflection = 1u << 1,
    kFeatureRefraction = 1u << 2,
    // Not an effect but a shape: the GPU traverses both levels in one loop (two_level_traversal.h),
    // with a register cap that keeps more warps in flight. A scene of many instances has it;
    // whether a frame keeps it is the traversal form's choice (traversal/traversal_form.h: the
    // CUDA frame renderer measures both forms; unmeasured, the nested form). On the H100 the
    // single loop made the instance grid 1.4-1.8x faster, while on the paper scene (one instance)
    // it is 1.2-1.5x slower than the nested form
    // (bench/results/gpu-register-cap-sweep-h100-2026-11-25.txt).
    kFeatureManyInstances = 1u << 3,
    // Materials with a base-colour texture: only these kernels interpolate uvs and sample.
    kFeatureTextures = 1u << 4,
    // glTF's metallic-roughness materials (pbr_material.h): only these kernels hold the BRDF.
    kFeaturePbr = 1u << 5,
};
inline constexpr uint32_t kAllFeatures =
    kFeatureShadows | kFeatureReflection | kFeatureRefraction | kFeatureTextures | kFeaturePbr;
inline constexpr uint32_t kAllFeatureBits = kAllFeatures | kFeatureManyInstances;
inline constexpr uint32_t kManyInstances = 64;

inline uint32_t InstanceCountFeatures(size_t instances) {
    return instances >= kManyInstances ? kFeatureManyInstances : 0u;
}

// What a pixel stores.
enum class ViewMode : uint32_t { kShaded = 0, kNormals = 1, kDepth = 2, kHeatmap = 3 };

}  // namespace rtrt
