#pragma once
// Runs the hard cases on the GPU: the evaluators of cases.h in kernels that nvcc compiles with
// its default floating-point contraction (--fmad=true), defined in gpu_runner.cu. The interface
// is CpuRunner's, so the checks of *_checks.h run unchanged on both back ends.
#include <span>
#include <string>
#include <vector>

#include "engine/render_rt/render_scene.h"
#include "tests/robust/cases.h"

namespace rtrt::robust {

struct GpuRunner {
    static constexpr const char* kName = "GPU";

    std::vector<uint32_t> Slab(std::span<const SlabCase> cases) const;
    std::vector<PrimResult> Sphere(std::span<const SphereCase> cases) const;
    std::vector<PrimResult> Triangle(std::span<const TriangleCase> cases) const;
    std::vector<SceneResult> Scene(const RenderScene& scene, std::span<const Ray> rays) const;
    std::vector<SpawnResult> Spawn(const RenderScene& scene,
                                   std::span<const SpawnCase> cases) const;
};

}  // namespace rtrt::robust
