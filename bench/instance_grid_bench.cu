#include <algorithm>
#include <cmath>

#include "bench/instance_grid_bench.h"
#include "engine/bvh/tlas/gpu_tlas.h"
#include "engine/bvh/tlas/tlas.h"
#include "engine/core/timer.h"
#include "engine/render_rt/cuda/cuda_trace.h"
#include "engine/render_rt/cuda/device_scene.h"
#include "engine/render_rt/pixel_kernel.h"
#include "game/scene/paper_scene.h"

namespace rtrt {
namespace {

constexpr int kBlock = 256;
constexpr float kSpacing = 1.5f;

// The benchmark's animation, one thread per instance: the record's transform (its TLAS words are
// the TLAS's).
__global__ void GridInstancesKernel(uint32_t n, uint32_t side, float time, Instance* out) {
    const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    const float half = 0.5f * float(side - 1);
    const vec3 cell(float(i % side), float((i / side) % side), float(i / (side * side)));
    const vec3 t = kSpacing * (cell - vec3(half)) + vec3(0.2f * sinf(time + float(i)), 0.0f, 0.0f);
    float s, c;
    sincosf(time + 0.37f * float(i), &s, &c);
    Instance inst;
    // Rotation about +y: x' = c x + s z, z' = -s x + c z; the inverse is the transpose.
    inst.inverseAndPosition.row[0] = vec4(c, 0.0f, -s, t.x);
    inst.inverseAndPosition.row[1] = vec4(0.0f, 1.0f, 0.0f, t.y);
    inst.inverseAndPosition.row[2] = vec4(s, 0.0f, c, t.z);
    inst.blasId = 0;
    inst.materialId = 0;
    SetPlacement(out[i], inst);
}

}  // namespace

std::vector<InstanceGridRow> RunInstanceGridBench(std::shared_ptr<const Blas> model,
                                                  const std::vector<uint32_t>& counts, int frames) {
    std::vector<InstanceGridRow> rows;
    const DeviceBuffer<Aabb> blasBounds(std::span<const Aabb>(&model->bounds, 1));
    const BlasOutline outline = OutlineOfBlas(*model);
    const DeviceBuffer<BlasOutline> blasOutline(std::span<const BlasOutline>(&outline, 1));
    RenderScene scene = MakePaperScene(model);  // BLAS, material, light; its one instance unused
    DeviceScene device(scene);
    for (uint32_t n : counts) {
        const uint32_t side = uint32_t(std::ceil(std::cbrt(double(n)) - 1e-9));
        const float h = 0.75f * float(side);
        scene.camera.position = vec3(0.0f, 0.0f, 3.2f * h + 2.0f);
        RenderSettings settings{kPaperWidth, kPaperHeight, kPaperMaxDepth};
        RenderSceneView view = device.View(scene, settings);
        DeviceBuffer<Instance> instances;
        instances.Resize(n);
        DeviceBuffer<vec3> frame;
        frame.Resize(size_t(settings.width) * settings.height);
        DeviceBuffer<unsigned long long> rayCount;
        rayCount.Resize(1);
        GpuTlas tlas;
        cudaEvent_t events[6];
        for (cudaEvent_t& e : events) RT_CUDA_CHECK(cudaEventCreate(&e));
        std::vector<double> update, build, refit, trace, total;
        InstanceGridRow row;
        row.instances = n;
        const uint32_t blocks = (n + kBlock - 1) / kBlock;
        const uint32_t features = scene.Features() | InstanceCountFeatures(n);
        for (int f = 0; f < 20 + frames; ++f) {
            const bool count = f == 0;
            if (count) RT_CUDA_CHECK(cudaMemset(rayCount.Data(), 0, sizeof(unsigned long long)));
            RT_CUDA_CHECK(cudaEventRecord(events[0]));
            GridInstancesKernel<<<blocks, kBlock>>>(n, side, 0.016f * float(f), instances.Data());
            RT_CUDA_CHECK_LAUNCH();
            RT_CUDA_CHECK(cudaEventRecord(events[1]));
            // The TLAS reads the instances' world boxes as it needs them (no array of them).
            tlas.Build(instances.Data(), {blasBounds.Data(), blasOutline.Data()}, n);
            RT_CUDA_CHECK(cudaEventRecord(events[2]));
            view.tlas = {tlas.Nodes(), instances.Data(), view.tlas.blases};
            LaunchTrace(view, ViewMode::kShaded, features, frame.Data(),
                        count ? rayCount.Data() : nullptr);
            RT_CUDA_CHECK(cudaEventRecord(events[3]));
            // The refit path, timed alone: same tree, the boxes this frame's rebuild used.
            RT_CUDA_CHECK(cudaEventRecord(events[4]));
            tlas.Refit(instances.Data(), {blasBounds.Data(), blasOutline.Data()});
            RT_CUDA_CHECK(cudaEventRecord(events[5]));
            RT_CUDA_CHECK(cudaEventSynchronize(events[5]));
            float refitMs = 0.0f;
            RT_CUDA_CHECK(cudaEventElapsedTime(&refitMs, events[4], events[5]));
            float ms[3];
            for (int s = 0; s < 3; ++s)
                RT_CUDA_CHECK(cudaEventElapsedTime(&ms[s], events[s], events[s + 1]));
            if (count) {
                unsigned long long rays = 0;
                rayCount.Download(std::span<unsigned long long>(&rays, 1));
                row.rays = rays;
            }
            if (f < 20) continue;
            update.push_back(ms[0]);
            build.push_back(ms[1]);
            refit.push_back(refitMs);
            trace.push_back(ms[2]);
            total.push_back(ms[0] + ms[1] + ms[2]);
        }
        for (cudaEvent_t e : events) RT_CUDA_CHECK(cudaEventDestroy(e));
        row.updateMs = Median(update);
        row.tlasMs = Median(build);
        row.refitMs = Median(refit);
        row.traceMs = Median(trace);
        row.totalMs = Median(total);
        // Per instance, as allocated: the records and the TLAS with every array its build keeps
        // (CUB's scratch included, where it does not fit in the node array).
        row.bytesPerInstance =
            double(instances.Size() * sizeof(Instance) + tlas.DeviceBytes()) / double(n);
        rows.push_back(row);
    }
    return rows;
}

}  // namespace rtrt
