#pragma once
// The CUDA trace kernel, its launch and its timing loop, as templates over the feature set and the
// trace policy (trace_policy.h): cuda_renderer.cu instantiates production's policy for every
// feature set, the accuracy study (bench/accuracy/accuracy_cuda.cu) its variants, so that both
// time the same kernel the same way.
#include <cooperative_groups.h>
#include <cuda_runtime.h>

#include <algorithm>
#include <span>
#include <vector>

#include "engine/core/cuda_check.h"
#include "engine/core/device_buffer.h"
#include "engine/render_rt/cuda/cuda_trace.h"
#include "engine/render_rt/pixel_kernel.h"
#include "engine/render_rt/split/frame_split.h"

namespace rtrt {

// Scenes of many instances trace with a register cap (blocks of 64 threads that must fit per
// SM): their time goes into long, divergent traversals that more warps in flight hide better.
// On the H100, 16 blocks (64 registers, some spilled) made the instance grid 1.6-1.8x faster than
// no cap (bench/results/gpu-register-cap-sweep-h100-2026-11-25.txt). The nested kernels without
// PBR are held to 128 registers (8 blocks, 16 warps per SM), which most need anyway: the
// refraction and texture kernels would take 132-137 and lose two warps per SM to a few
// registers (bench/results/gpu-header-carry-h200-2026-12-03.txt). PBR kernels (160-175
// registers) run uncapped. cmake -DRTRT_TRACE_MIN_BLOCKS=N overrides the many-instance cap, for
// experiments.
#if !defined(RTRT_TRACE_MIN_BLOCKS)
#define RTRT_TRACE_MIN_BLOCKS 16
#endif
constexpr int TraceMinBlocks(uint32_t features) {
    if ((features & kFeatureManyInstances) != 0) return RTRT_TRACE_MIN_BLOCKS;
    return (features & kFeaturePbr) != 0 ? 1 : 8;
}

template <uint32_t kFeatures, class Policy>
__global__ void __launch_bounds__(64, TraceMinBlocks(kFeatures))
    TraceKernel(RenderSceneView scene, ViewMode view, uint32_t sample, uint32_t perSide,
                uint32_t rowBegin, uint32_t rowEnd, vec3* out, unsigned long long* rayCount) {
    const uint32_t x = blockIdx.x * blockDim.x + threadIdx.x;
    const uint32_t y = rowBegin + blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= scene.width || y >= rowEnd) return;
    uint32_t rays = 0;
    const vec3 value = RawSample<kFeatures, Policy>(scene, view, x, y, sample, perSide, &rays);
    AccumulateSample(out[size_t(y) * scene.width + x], value, sample, perSide * perSide);
    if (rayCount) atomicAdd(rayCount, (unsigned long long)rays);
}

// The shaded view in two kernels. The first finds every pixel's primary hit with the scene
// traversal alone, so it needs far fewer registers than shading and keeps more warps in flight;
// a miss is finished there (the background), a hit is queued. The second runs the rest of the
// pixel's TraceRay from the queued hit, one queue entry per thread: its warps are full where the
// one-kernel form's warps along a silhouette run with the lanes of missed pixels idle. Each pixel
// is written by one thread with TraceRay's operations in TraceRay's order, so the queue's order
// (which the atomic counter makes vary) changes nothing in the image.
#if !defined(RTRT_PRIMARY_MIN_BLOCKS)
#define RTRT_PRIMARY_MIN_BLOCKS 16
#endif
template <uint32_t kShape, class Policy>
__global__ void __launch_bounds__(64, RTRT_PRIMARY_MIN_BLOCKS)
    PrimaryHitKernel(RenderSceneView scene, uint32_t sample, uint32_t perSide, uint32_t rowBegin,
                     uint32_t rowEnd, vec3* out, QueuedPrimaryHit* queue, uint32_t* queued,
                     unsigned long long* rayCount) {
    const uint32_t x = blockIdx.x * blockDim.x + threadIdx.x;
    const uint32_t y = rowBegin + blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= scene.width || y >= rowEnd) return;
    const vec2 at = PixelSample(x, y, sample, perSide);
    const Ray ray =
        PrimaryRay(scene.camera, float(x) + at.x, float(y) + at.y, scene.width, scene.height);
    const uint32_t pixel = y * scene.width + x;
    SceneHit hit;
    if (!TraceIntersect<kShape, Policy>(scene.tlas, ray, &hit, nullptr)) {
        // TraceRay's colour of a pixel whose primary ray misses: 0 + 1 * background.
        AccumulateSample(out[pixel], scene.background, sample, perSide * perSide);
        if (rayCount) atomicAdd(rayCount, 1ull);
        return;
    }
    namespace cg = cooperative_groups;
    const cg::coalesced_group hits = cg::coalesced_threads();
    uint32_t first = 0;
    if (hits.thread_rank() == 0) first = atomicAdd(queued, hits.size());
    first = hits.shfl(first, 0);
    queue[first + hits.thread_rank()] = {ray, hit, pixel, {0, 0}};
}

template <uint32_t kFeatures, class Policy>
__global__ void __launch_bounds__(64, TraceMinBlocks(kFeatures))
    ShadeQueuedKernel(RenderSceneView scene, uint32_t sample, uint32_t perSide,
                      const QueuedPrimaryHit* queue, const uint32_t* queued, vec3* out,
                      unsigned long long* rayCount) {
    const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= *queued) return;
    const QueuedPrimaryHit q = queue[i];
    const PixelResult r = TraceRay<kFeatures, Policy>(scene, q.ray, false, &q.hit);
    AccumulateSample(out[q.pixel], r.color, sample, perSide * perSide);
    if (rayCount) atomicAdd(rayCount, (unsigned long long)r.rays);
}

// Traces view (all pointers in device memory) into frame (width x height, device memory), the
// rows of `rows` only (default: all); rayCount, if not null, accumulates the rays traced.
template <uint32_t kFeatures, class Policy = TracePolicy>
void LaunchTraceKernel(const RenderSceneView& view, ViewMode mode, vec3* frame,
                       unsigned long long* rayCount, cudaStream_t stream = 0,
                       RowBand rows = {0, UINT32_MAX}, TraceWorkspace* workspace = nullptr) {
    const uint32_t rowEnd = std::min(rows.end, view.height);
    if (rows.begin >= rowEnd) return;
    const dim3 block(8, 8);
    const dim3 grid((view.width + block.x - 1) / block.x,
                    (rowEnd - rows.begin + block.y - 1) / block.y);
    // One launch per sample (AccumulateSample says why).
    const uint32_t perSide = SamplesPerSide(view, mode);
    constexpr bool kTwoKernelSet = (kFeatures & (kFeatureTextures | kFeaturePbr)) == 0;
    if (kTwoKernelSet && workspace && mode == ViewMode::kShaded) {
        QueuedPrimaryHit* queue = workspace->Queue() + size_t(rows.begin) * view.width;
        uint32_t* queued = workspace->Counters() + rows.begin;
        const uint32_t pixels = (rowEnd - rows.begin) * view.width;
        for (uint32_t s = 0; s < perSide * perSide; ++s) {
            RT_CUDA_CHECK(cudaMemsetAsync(queued, 0, sizeof(uint32_t), stream));
            if constexpr (kTwoKernelSet) {
                PrimaryHitKernel<kFeatures & kFeatureManyInstances, Policy>
                    <<<grid, block, 0, stream>>>(view, s, perSide, rows.begin, rowEnd, frame, queue,
                                                 queued, rayCount);
                RT_CUDA_CHECK_LAUNCH();
                ShadeQueuedKernel<kFeatures, Policy><<<(pixels + 63) / 64, 64, 0, stream>>>(
                    view, s, perSide, queue, queued, frame, rayCount);
                RT_CUDA_CHECK_LAUNCH();
            }
        }
        return;
    }
    for (uint32_t s = 0; s < perSide * perSide; ++s) {
        TraceKernel<kFeatures, Policy><<<grid, block, 0, stream>>>(
            view, mode, s, perSide, rows.begin, rowEnd, frame, rayCount);
        RT_CUDA_CHECK_LAUNCH();
    }
}

}  // namespace rtrt
