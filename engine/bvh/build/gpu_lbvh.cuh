#pragma once
// GpuLbvh's build and refit over any Boxes (lbvh_steps.h), for .cu files: gpu_lbvh.cu instantiates
// them for arrays of boxes. The centroids' reduction serves the GPU TLAS too (gpu_tlas.cu).
#include <cub/cub.cuh>
#include <utility>

#include "engine/bvh/build/gpu_lbvh.h"
#include "engine/bvh/build/lbvh_steps.h"
#include "engine/core/parallel_for_cuda.h"

namespace rtrt {

// The centroids' bounds as OrderedBounds (set to kNone before): each thread takes the keys of a
// stride of primitives, each warp its lanes' minima, and one lane per warp the atomic minima.
template <class Boxes>
__global__ void LbvhCentroidBoundsKernel(Boxes bounds, uint32_t n, OrderedBounds* out) {
    uint32_t keys[6];
    for (uint32_t& k : keys) k = OrderedBounds::kNone;
    for (uint32_t i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x) {
        const vec3 c = Aabb(bounds[i]).Centroid();
        for (int a = 0; a < 3; ++a) {
            keys[a] = min(keys[a], OrderedBounds::MinKey(c[a]));
            keys[3 + a] = min(keys[3 + a], OrderedBounds::NegMaxKey(c[a]));
        }
    }
    for (uint32_t& k : keys) k = __reduce_min_sync(0xffffffffu, k);
    if (threadIdx.x % 32 != 0) return;
    for (int a = 0; a < 3; ++a) {
        if (keys[a] != OrderedBounds::kNone) atomicMin(&out->minKey[a], keys[a]);
        if (keys[3 + a] != OrderedBounds::kNone) atomicMin(&out->negMaxKey[a], keys[3 + a]);
    }
}

template <class Boxes>
void GpuLbvh::BuildOver(Boxes bounds, uint32_t n, cudaStream_t stream) {
    count_ = n;
    const size_t positions = std::max<size_t>(2, 2 * size_t(n));
    nodes_.Resize(positions);
    parents_.Resize(positions);
    primOrder_.Resize(n);
    if (n == 0) {
        RT_CUDA_CHECK(cudaMemsetAsync(parents_.Data(), 0xff, positions * sizeof(uint32_t), stream));
        const BvhNode empty{vec3(kInfinity), 0, vec3(-kInfinity), 0};
        const BvhNode host[2] = {empty, empty};  // as the CPU build leaves an empty tree
        RT_CUDA_CHECK(
            cudaMemcpyAsync(nodes_.Data(), host, sizeof(host), cudaMemcpyHostToDevice, stream));
        RT_CUDA_CHECK(cudaStreamSynchronize(stream));
        return;
    }
    RT_CUDA_CHECK(cudaMemsetAsync(nodes_.Data() + 1, 0, sizeof(BvhNode), stream));
    spareIndices_.Resize(n);
    centroidBounds_.Resize(1);

    // The sort ping-pongs between the two arrays of each pair (CUB's double buffer), which
    // spares the scratch a copy of both. The codes' two arrays are the halves of the parent
    // links, which are written only once the codes have been read (below).
    uint32_t* const codes = parents_.Data();
    cub::DoubleBuffer<uint32_t> keys(codes, codes + n);
    cub::DoubleBuffer<uint32_t> values(spareIndices_.Data(), primOrder_.Data());
    size_t sortBytes = 0;
    RT_CUDA_CHECK(
        cub::DeviceRadixSort::SortPairs(nullptr, sortBytes, keys, values, int(n), 0, 30, stream));
    if (scratch_.Size() < sortBytes) scratch_.Resize(sortBytes);

    RT_CUDA_CHECK(cudaMemsetAsync(centroidBounds_.Data(), 0xff, sizeof(OrderedBounds), stream));
    constexpr uint32_t kBlock = 256, kMaxBlocks = 1024;  // a few per SM: few atomics
    const uint32_t blocks = std::min((n + kBlock - 1) / kBlock, kMaxBlocks);
    LbvhCentroidBoundsKernel<<<blocks, kBlock, 0, stream>>>(bounds, n, centroidBounds_.Data());
    RT_CUDA_CHECK_LAUNCH();
    ParallelForCuda(0, n,
                    LbvhMortonCodes<Boxes, OrderedBounds>{bounds, centroidBounds_.Data(), codes,
                                                          spareIndices_.Data()},
                    stream);
    RT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(scratch_.Data(), sortBytes, keys, values, int(n),
                                                  0, 30, stream));
    // The sorted values are wherever the last pass left them: name them primOrder_.
    if (values.Current() != primOrder_.Data()) std::swap(spareIndices_, primOrder_);
    if (n == 1) {
        RT_CUDA_CHECK(cudaMemsetAsync(parents_.Data(), 0xff, positions * sizeof(uint32_t), stream));
        ParallelForCuda(0, 1, LbvhRootLeaf<Boxes>{bounds, primOrder_.Data(), nodes_.Data()},
                        stream);
        RT_CUDA_CHECK(cudaStreamSynchronize(stream));
        return;
    }
    ParallelForCuda(
        0, n - 1,
        LbvhKarrasNodes<Boxes>{keys.Current(), n, primOrder_.Data(), bounds, nodes_.Data()},
        stream);
    // The codes are read: the parent links take their memory back.
    RT_CUDA_CHECK(cudaMemsetAsync(parents_.Data(), 0xff, positions * sizeof(uint32_t), stream));
    ParallelForCuda(0, positions,
                    LbvhLinkNodes<LbvhPositionParents>{nodes_.Data(), {parents_.Data()}}, stream);
    BoundsBottomUp(stream);
}

template <class Boxes>
void GpuLbvh::RefitOver(Boxes bounds, cudaStream_t stream) {
    if (count_ == 0) return;
    if (count_ == 1) {
        ParallelForCuda(0, 1, LbvhRootLeaf<Boxes>{bounds, primOrder_.Data(), nodes_.Data()},
                        stream);
        return;
    }
    const uint32_t positions = 2 * count_;
    ParallelForCuda(0, positions - 2,
                    LbvhRefitLeaves<Boxes>{bounds, primOrder_.Data(), nodes_.Data()}, stream);
    BoundsBottomUp(stream);
}

}  // namespace rtrt
