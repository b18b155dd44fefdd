#pragma once
// The CUDA trace kernel, its launch and its timing loop, as templates over the feature set and the
// trace policy (trace_policy.h): cuda_renderer.cu instantiates production's policy for every
// feature set, the accuracy study (bench/accuracy/accuracy_cuda.cu) its variants, so that both
// time the same kernel the same way.
#include <cuda_runtime.h>

#include <algorithm>
#include <span>
#include <vector>

#include "engine/core/cuda_check.h"
#include "engine/core/device_buffer.h"
#include "engine/render_rt/pixel_kernel.h"
#include "engine/render_rt/split/frame_split.h"

namespace rtrt {

// The single-loop kernels (kFeatureManyInstances) trace with a register cap (blocks of 64 threads
// that must fit per SM): their time goes into long, divergent traversals that more warps in flight
// hide better. On the H100, 16 blocks (64 registers, some spilled) made the instance grid 1.6-1.8x
// faster than no cap (bench/results/gpu-register-cap-sweep-h100-2026-11-25.txt). The nested kernels
// are held to 128 registers (16 warps per SM), which most need anyway: the refraction and texture
// kernels would take 132-137 and lose two warps per SM to a few registers
// (bench/results/gpu-header-carry-h200-2026-12-03.txt). The PBR kernels would take 160-175 and
// hold 10-12 warps; held to 128 they traced demo_crowd faster for a little more time on the
// lighter gltf_demo, and 102 registers cost gltf_demo far more
// (bench/results/pbr-register-cap-h100-2026-12-06.txt). cmake -DRTRT_TRACE_MIN_BLOCKS=N overrides
// the many-instance cap (in blocks of 64 threads), for experiments.
#if !defined(RTRT_TRACE_MIN_BLOCKS)
#define RTRT_TRACE_MIN_BLOCKS 16
#endif

// Rows of pixels a block traces, 8 pixels wide: warps of 8 x 4 pixels stacked. The nested kernels
// trace 8 x 16 (four warps), so that the warps an SM holds at once come from fewer, larger patches
// of the image and can share more of the BVH in its L1; the paper scene, three of the played demos
// and, once held to 128 registers, the PBR scenes traced faster so. The single loop traced the
// instance grid no faster, and blocks of one warp were slower everywhere
// (bench/results/trace-tiles-h100-2026-12-06.txt, pbr-tiles-h100-2026-12-06.txt,
// trace-profile-h200-2026-12-03.txt): the single loop keeps 8 x 8.
constexpr uint32_t TraceBlockRows(uint32_t features) {
    return (features & kFeatureManyInstances) != 0 ? 8u : 16u;
}
constexpr uint32_t TraceBlockThreads(uint32_t features) { return 8u * TraceBlockRows(features); }

// Blocks per SM that the register caps above ask for, in blocks of TraceBlockThreads: the threads
// an SM must hold (RTRT_TRACE_MIN_BLOCKS blocks of 64, or 16 warps for the 128-register cap)
// divided by the block's.
constexpr int TraceMinBlocks(uint32_t features) {
    const int threads = int(TraceBlockThreads(features));
    if ((features & kFeatureManyInstances) != 0) return RTRT_TRACE_MIN_BLOCKS * 64 / threads;
    constexpr int kNestedThreadsPerSm = 16 * 32;
    return kNestedThreadsPerSm / threads;
}

template <uint32_t kFeatures, class Policy>
__global__ void __launch_bounds__(TraceBlockThreads(kFeatures), TraceMinBlocks(kFeatures))
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

// Traces view (all pointers in device memory) into frame (width x height, device memory), the
// rows of `rows` only (default: all); rayCount, if not null, accumulates the rays traced.
template <uint32_t kFeatures, class Policy = TracePolicy>
void LaunchTraceKernel(const RenderSceneView& view, ViewMode mode, vec3* frame,
                       unsigned long long* rayCount, cudaStream_t stream = 0,
                       RowBand rows = {0, UINT32_MAX}) {
    const uint32_t rowEnd = std::min(rows.end, view.height);
    if (rows.begin >= rowEnd) return;
    const dim3 block(8, TraceBlockRows(kFeatures));
    const dim3 grid((view.width + block.x - 1) / block.x,
                    (rowEnd - rows.begin + block.y - 1) / block.y);
    // One launch per sample (AccumulateSample says why).
    const uint32_t perSide = SamplesPerSide(view, mode);
    for (uint32_t s = 0; s < perSide * perSide; ++s) {
        TraceKernel<kFeatures, Policy><<<grid, block, 0, stream>>>(
            view, mode, s, perSide, rows.begin, rowEnd, frame, rayCount);
        RT_CUDA_CHECK_LAUNCH();
    }
}

}  // namespace rtrt
