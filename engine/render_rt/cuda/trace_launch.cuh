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
#include "engine/render_rt/cuda/primary_hits.h"
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
                uint32_t rowBegin, uint32_t rowEnd, vec3* out, unsigned long long* rayCount,
                const SceneHit* primaryHits) {
    const uint32_t x = blockIdx.x * blockDim.x + threadIdx.x;
    const uint32_t y = rowBegin + blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= scene.width || y >= rowEnd) return;
    uint32_t rays = 0;
    // Only the many-instance kernels take primary hits: the others keep the code they had.
    const SceneHit* primaryHit = (kFeatures & kFeatureManyInstances) != 0 && primaryHits != nullptr
                                     ? primaryHits + size_t(y) * scene.width + x
                                     : nullptr;
    const vec3 value =
        RawSample<kFeatures, Policy>(scene, view, x, y, sample, perSide, &rays, primaryHit);
    AccumulateSample(out[size_t(y) * scene.width + x], value, sample, perSide * perSide);
    if (rayCount) atomicAdd(rayCount, (unsigned long long)rays);
}

// The primary hits of a band of a scene of many instances, before the pixels are shaded. The
// lanes of a warp trace different rays for very different lengths (through one instance or ten),
// and a warp runs as long as its longest ray: here a lane whose ray is done takes up the next
// one from the band's cursor while the others go on, so lanes rarely idle (Aila and Laine 2009,
// "replacing terminated rays"). Rays are handed out in warp tiles of 8 x 4 pixels, in the order
// of the trace kernel's blocks, so that a warp starts on neighbouring rays; a warp refills once
// at least kRefillLanes lanes are free, one atomic add for all of them. The hit is the one
// TraceRay's own traversal would find (the same walk on the same ray).
inline constexpr uint32_t kRefillLanes = 8;
inline constexpr uint32_t kIdleLane = 0xffffffffu;

template <class Policy>
__global__ void __launch_bounds__(64, RTRT_TRACE_MIN_BLOCKS)
    PrimaryHitKernel(RenderSceneView scene, uint32_t sample, uint32_t perSide, uint32_t rowBegin,
                     uint32_t rowEnd, uint32_t* cursor, SceneHit* hits) {
    const uint32_t lane = threadIdx.x & 31u;
    const uint32_t tilesPerRow = (scene.width + 7) / 8;
    const uint32_t rays = tilesPerRow * ((rowEnd - rowBegin + 3) / 4) * 32;
    uint32_t stack[kTwoLevelStackSize];
    TwoLevelWalk<Query::kIntersect, Policy> walk(stack);
    Ray ray;
    SceneHit hit;
    uint32_t pixel = kIdleLane;  // y * width + x of the lane's ray
    bool drained = false;        // the cursor has passed the last ray (the same in every lane)
    for (;;) {
        const uint32_t idleLanes = __ballot_sync(~0u, pixel == kIdleLane);
        if (!drained && uint32_t(__popc(idleLanes)) >= kRefillLanes) {
            const int leader = __ffs(idleLanes) - 1;
            uint32_t base = 0;
            if (int(lane) == leader) base = atomicAdd(cursor, uint32_t(__popc(idleLanes)));
            base = __shfl_sync(~0u, base, leader);
            drained = base + uint32_t(__popc(idleLanes)) >= rays;
            const uint32_t index = base + __popc(idleLanes & ((1u << lane) - 1u));
            if (pixel == kIdleLane && index < rays) {
                const uint32_t tile = index / 32, within = index % 32;
                const uint32_t x = (tile % tilesPerRow) * 8 + within % 8;
                const uint32_t y = rowBegin + (tile / tilesPerRow) * 4 + within / 8;
                if (x < scene.width && y < rowEnd) {
                    ray = SamplePrimaryRay(scene, x, y, sample, perSide);
                    pixel = y * scene.width + x;
                    if (!walk.Begin(scene.tlas, ray, ray.tMax, nullptr)) {
                        hits[pixel].instance = kNoHitInstance;
                        pixel = kIdleLane;
                    }
                }
            }
        }
        const bool busy = pixel != kIdleLane;
        if (__ballot_sync(~0u, busy) == 0) {
            if (drained) return;
            continue;
        }
        if (busy && walk.Step(scene.tlas, ray, &hit, nullptr)) {
            if (!walk.Found()) hit.instance = kNoHitInstance;
            hits[pixel] = hit;
            pixel = kIdleLane;
        }
    }
}

// How many blocks of the primary-hit kernel fit on the device at once: it is launched with as
// many, each warp taking rays until the band's run out.
template <class Policy>
uint32_t ResidentPrimaryHitBlocks() {
    static const uint32_t blocks = [] {
        int device = 0, sms = 0, perSm = 0;
        RT_CUDA_CHECK(cudaGetDevice(&device));
        RT_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device));
        RT_CUDA_CHECK(
            cudaOccupancyMaxActiveBlocksPerMultiprocessor(&perSm, PrimaryHitKernel<Policy>, 64, 0));
        return uint32_t(std::max(1, sms * std::max(1, perSm)));
    }();
    return blocks;
}

// Traces view (all pointers in device memory) into frame (width x height, device memory), the
// rows of `rows` only (default: all); rayCount, if not null, accumulates the rays traced. With
// primary's buffers, scenes of many instances find their primary hits first (PrimaryHitKernel).
template <uint32_t kFeatures, class Policy = TracePolicy>
void LaunchTraceKernel(const RenderSceneView& view, ViewMode mode, vec3* frame,
                       unsigned long long* rayCount, cudaStream_t stream = 0,
                       RowBand rows = {0, UINT32_MAX}, PrimaryHitScratch primary = {}) {
    const uint32_t rowEnd = std::min(rows.end, view.height);
    if (rows.begin >= rowEnd) return;
    const dim3 block(8, 8);
    const dim3 grid((view.width + block.x - 1) / block.x,
                    (rowEnd - rows.begin + block.y - 1) / block.y);
    // One launch per sample (AccumulateSample says why).
    const uint32_t perSide = SamplesPerSide(view, mode);
    // The primary-hit kernel serves the single loop over both levels (scenes of many instances),
    // in every view but the heatmap, which counts the primary ray's own traversal.
    const bool primaryFirst = (kFeatures & kFeatureManyInstances) != 0 &&
                              mode != ViewMode::kHeatmap && primary.hits != nullptr &&
                              !AnswersSceneQueries<Policy>;
    for (uint32_t s = 0; s < perSide * perSide; ++s) {
        if (primaryFirst) {
            RT_CUDA_CHECK(cudaMemsetAsync(primary.cursor, 0, sizeof(uint32_t), stream));
            PrimaryHitKernel<Policy><<<ResidentPrimaryHitBlocks<Policy>(), 64, 0, stream>>>(
                view, s, perSide, rows.begin, rowEnd, primary.cursor, primary.hits);
            RT_CUDA_CHECK_LAUNCH();
        }
        TraceKernel<kFeatures, Policy>
            <<<grid, block, 0, stream>>>(view, mode, s, perSide, rows.begin, rowEnd, frame,
                                         rayCount, primaryFirst ? primary.hits : nullptr);
        RT_CUDA_CHECK_LAUNCH();
    }
}

}  // namespace rtrt
