#pragma once
// Runs the hard cases on the CPU: the evaluators of cases.h in a TBB loop, compiled like the
// renderer's host code (-ffp-contract=off).
#include <tbb/parallel_for.h>

#include <span>
#include <vector>

#include "engine/render_rt/render_scene.h"
#include "tests/robust/cases.h"

namespace rtrt::robust {

struct CpuRunner {
    static constexpr const char* kName = "CPU";

    template <typename Case, typename Eval>
    static auto Map(std::span<const Case> cases, const Eval& eval) {
        std::vector<decltype(eval(cases[0]))> out(cases.size());
        tbb::parallel_for(size_t(0), cases.size(), [&](size_t i) { out[i] = eval(cases[i]); });
        return out;
    }

    std::vector<uint32_t> Slab(std::span<const SlabCase> cases) const {
        return Map(cases, [](const SlabCase& c) { return EvaluateSlab(c); });
    }
    std::vector<PrimResult> Sphere(std::span<const SphereCase> cases) const {
        return Map(cases, [](const SphereCase& c) { return EvaluateSphere(c); });
    }
    std::vector<PrimResult> Triangle(std::span<const TriangleCase> cases) const {
        return Map(cases, [](const TriangleCase& c) { return EvaluateTriangle(c); });
    }
    // The scene's TLAS must be built.
    std::vector<SceneResult> Scene(const RenderScene& scene, std::span<const Ray> rays) const {
        const SceneEvaluator eval{scene.HostView(1, 1, 1).tlas, uint32_t(scene.instances.size())};
        return Map(rays, eval);
    }
    std::vector<SpawnResult> Spawn(const RenderScene& scene,
                                   std::span<const SpawnCase> cases) const {
        return Map(cases, SpawnEvaluator{scene.HostView(1, 1, 1).tlas});
    }
};

}  // namespace rtrt::robust
