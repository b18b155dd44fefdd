#pragma once
// The renderers of `rtrt bench accuracy`: the float trace with accuracy variants
// (bench/accuracy/accuracy_policy.h) on either back end, and the double-precision reference on the
// CPU. The variants are instantiated here only, for the one effect set of the benchmark's scenes
// (kAccuracyFeatures), so the default kernels and the build time of everything else stay as they
// were; on the GPU, in the traversal form the scene's instance count selects (trace.h).
#include <string>
#include <vector>

#include "engine/render_rt/renderer.h"

namespace rtrt {

inline constexpr uint32_t kAccuracyFeatures = kAllFeatures;

// Primary hit object of each pixel centre's ray: 0 for a miss, else instance index + 1.
using ObjectIds = std::vector<uint32_t>;

void RenderAccuracyCpu(const RenderScene& scene, const RenderSettings& settings, uint32_t accuracy,
                       Image& image, RenderStats* stats = nullptr);
ObjectIds PrimaryObjectsCpu(const RenderScene& scene, const RenderSettings& settings,
                            uint32_t accuracy);

// Double precision throughout (reference_trace.h), every effect on.
Image RenderReference(const RenderScene& scene, const RenderSettings& settings);
ObjectIds ReferencePrimaryObjects(const RenderScene& scene, const RenderSettings& settings);

// The CUDA back end: `warmup` untimed and `frames` timed trace launches (CUDA events), then the
// image and the primary objects. Throws std::runtime_error without a usable GPU.
struct CudaAccuracyRun {
    std::vector<double> traceMs;
    Image image;
    ObjectIds objects;
    uint64_t rays = 0;
};
CudaAccuracyRun RunAccuracyCuda(const RenderScene& scene, const RenderSettings& settings,
                                uint32_t accuracy, int warmup, int frames);

}  // namespace rtrt
