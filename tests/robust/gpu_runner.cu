// The GPU runner: one thread per case, the RT_HD evaluators of cases.h. No --use_fast_math and no
// --fmad=false: the cases must hold under nvcc's default contraction, which fuses every
// multiply-add the code does not keep apart itself (triangle_intersect.h keeps the edge
// functions apart with __fmul_rn/__fsub_rn).
#include "engine/core/device_buffer.h"
#include "engine/render_rt/cuda/device_scene.h"
#include "tests/robust/gpu_runner.h"

namespace rtrt::robust {
namespace {

template <typename Case, typename Result, typename Eval>
__global__ void MapKernel(Eval eval, const Case* cases, Result* out, uint32_t n) {
    const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n) out[i] = eval(cases[i]);
}

template <typename Result, typename Case, typename Eval>
std::vector<Result> Map(std::span<const Case> cases, const Eval& eval) {
    std::vector<Result> out(cases.size());
    if (cases.empty()) return out;
    DeviceBuffer<Case> in(cases);
    DeviceBuffer<Result> results;
    results.Resize(cases.size());
    constexpr uint32_t kBlock = 128;
    const uint32_t n = uint32_t(cases.size());
    MapKernel<<<(n + kBlock - 1) / kBlock, kBlock>>>(eval, in.Data(), results.Data(), n);
    RT_CUDA_CHECK_LAUNCH();
    RT_CUDA_CHECK(cudaDeviceSynchronize());
    results.Download(out);
    return out;
}

struct SlabEval {
    RT_HD uint32_t operator()(const SlabCase& c) const { return EvaluateSlab(c); }
};
struct SphereEval {
    RT_HD PrimResult operator()(const SphereCase& c) const { return EvaluateSphere(c); }
};
struct TriangleEval {
    RT_HD PrimResult operator()(const TriangleCase& c) const { return EvaluateTriangle(c); }
};

TlasView DeviceTlas(const DeviceStaticScene& device, const RenderScene& scene) {
    RenderSettings settings;
    settings.width = settings.height = 1;
    return device.View(scene, settings).tlas;
}

}  // namespace

std::vector<uint32_t> GpuRunner::Slab(std::span<const SlabCase> cases) const {
    return Map<uint32_t>(cases, SlabEval{});
}
std::vector<PrimResult> GpuRunner::Sphere(std::span<const SphereCase> cases) const {
    return Map<PrimResult>(cases, SphereEval{});
}
std::vector<PrimResult> GpuRunner::Triangle(std::span<const TriangleCase> cases) const {
    return Map<PrimResult>(cases, TriangleEval{});
}
std::vector<SceneResult> GpuRunner::Scene(const RenderScene& scene,
                                          std::span<const Ray> rays) const {
    const DeviceStaticScene device(scene);
    return Map<SceneResult>(
        rays, SceneEvaluator{DeviceTlas(device, scene), uint32_t(scene.instances.size())});
}
std::vector<SpawnResult> GpuRunner::Spawn(const RenderScene& scene,
                                          std::span<const SpawnCase> cases) const {
    const DeviceStaticScene device(scene);
    return Map<SpawnResult>(cases, SpawnEvaluator{DeviceTlas(device, scene)});
}

}  // namespace rtrt::robust
