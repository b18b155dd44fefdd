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
// without PBR are held to 128 registers (8 blocks, 16 warps per SM), which most need anyway: the
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

// One sample of pixel (x, y) into out, its rays counted into rayCount if not null.
template <uint32_t kFeatures, class Policy>
__device__ inline void TracePixelSample(const RenderSceneView& scene, ViewMode view, uint32_t x,
                                        uint32_t y, uint32_t sample, uint32_t perSide, vec3* out,
                                        unsigned long long* rayCount) {
    uint32_t rays = 0;
    const vec3 value = RawSample<kFeatures, Policy>(scene, view, x, y, sample, perSide, &rays);
    AccumulateSample(out[size_t(y) * scene.width + x], value, sample, perSide * perSide);
    if (rayCount) atomicAdd(rayCount, (unsigned long long)rays);
}

// One thread per pixel in blocks of 8 x 8.
template <uint32_t kFeatures, class Policy>
__global__ void __launch_bounds__(64, TraceMinBlocks(kFeatures))
    TraceKernel(RenderSceneView scene, ViewMode view, uint32_t sample, uint32_t perSide,
                uint32_t rowBegin, uint32_t rowEnd, vec3* out, unsigned long long* rayCount) {
    const uint32_t x = blockIdx.x * blockDim.x + threadIdx.x;
    const uint32_t y = rowBegin + blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= scene.width || y >= rowEnd) return;
    TracePixelSample<kFeatures, Policy>(scene, view, x, y, sample, perSide, out, rayCount);
}

// Persistent warps: as many blocks of 64 threads as fit on the GPU at once, each warp taking 8 x 4
// pixel tiles, row by row, from a frame-wide cursor (one atomic add per tile) until none are left.
// The many-instance kernels launch this way: their rays are long and uneven, and a warp that
// finishes takes new work at once instead of waiting for the other warp of its block. On the H100
// the instance grid traced 2.0-3.2% faster with it and the explicit fusing of mul_add.h than before
// either, and a version of it took 3.8-4.1% off while the compiler fused at will
// (bench/results/persistent-warps-fmad-h100-2026-12-06.txt).
// The nested kernels keep the block grid: their rays are mostly short (background, small models),
// and the paper scene's cube and teapot traced 8-9% slower
// (bench/results/persistent-warps-h100-2026-12-06.txt). A warp traces the same 8 x 4 pixels as in
// the block grid, and the device code fuses no multiply-add it was not asked to (mul_add.h), so
// both kernels give the same pixels bit for bit.
template <uint32_t kFeatures, class Policy>
__global__ void __launch_bounds__(64, TraceMinBlocks(kFeatures))
    PersistentTraceKernel(RenderSceneView scene, ViewMode view, uint32_t sample, uint32_t perSide,
                          uint32_t rowBegin, uint32_t rowEnd, vec3* out,
                          unsigned long long* rayCount, uint32_t* tileCursor) {
    const uint32_t lane = threadIdx.x & 31u;
    const uint32_t tilesX = (scene.width + 7) / 8;
    const uint32_t tiles = tilesX * ((rowEnd - rowBegin + 3) / 4);
    for (;;) {
        uint32_t tile = 0;
        if (lane == 0) tile = atomicAdd(tileCursor, 1u);
        tile = __shfl_sync(0xffffffffu, tile, 0);
        if (tile >= tiles) return;
        const uint32_t x = (tile % tilesX) * 8 + (lane & 7u);
        const uint32_t y = rowBegin + (tile / tilesX) * 4 + (lane >> 3);
        if (x < scene.width && y < rowEnd)
            TracePixelSample<kFeatures, Policy>(scene, view, x, y, sample, perSide, out, rayCount);
    }
}

// How many blocks of PersistentTraceKernel fit on the current device at once.
template <uint32_t kFeatures, class Policy>
uint32_t PersistentBlocks() {
    int device = 0, sms = 0, perSm = 0;
    RT_CUDA_CHECK(cudaGetDevice(&device));
    RT_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device));
    RT_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(
        &perSm, PersistentTraceKernel<kFeatures, Policy>, 64, 0));
    return uint32_t(std::max(1, sms * perSm));
}

// Traces view (all pointers in device memory) into frame (width x height, device memory), the
// rows of `rows` only (default: all); rayCount, if not null, accumulates the rays traced. A
// many-instance kernel runs persistent when given tileCursor, one word of device memory that no
// other launch uses meanwhile (it is reset on the stream first); without one, and for the other
// kernels, the block grid traces.
template <uint32_t kFeatures, class Policy = TracePolicy>
void LaunchTraceKernel(const RenderSceneView& view, ViewMode mode, vec3* frame,
                       unsigned long long* rayCount, cudaStream_t stream = 0,
                       RowBand rows = {0, UINT32_MAX}, uint32_t* tileCursor = nullptr) {
    const uint32_t rowEnd = std::min(rows.end, view.height);
    if (rows.begin >= rowEnd) return;
    // One launch per sample (AccumulateSample says why).
    const uint32_t perSide = SamplesPerSide(view, mode);
    if constexpr ((kFeatures & kFeatureManyInstances) != 0) {
        if (tileCursor) {
            const uint32_t blocks = PersistentBlocks<kFeatures, Policy>();
            for (uint32_t s = 0; s < perSide * perSide; ++s) {
                RT_CUDA_CHECK(cudaMemsetAsync(tileCursor, 0, sizeof(uint32_t), stream));
                PersistentTraceKernel<kFeatures, Policy><<<blocks, 64, 0, stream>>>(
                    view, mode, s, perSide, rows.begin, rowEnd, frame, rayCount, tileCursor);
                RT_CUDA_CHECK_LAUNCH();
            }
            return;
        }
    }
    const dim3 block(8, 8);
    const dim3 grid((view.width + block.x - 1) / block.x,
                    (rowEnd - rows.begin + block.y - 1) / block.y);
    for (uint32_t s = 0; s < perSide * perSide; ++s) {
        TraceKernel<kFeatures, Policy><<<grid, block, 0, stream>>>(
            view, mode, s, perSide, rows.begin, rowEnd, frame, rayCount);
        RT_CUDA_CHECK_LAUNCH();
    }
}

}  // namespace rtrt
