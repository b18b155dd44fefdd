#pragma once
// GpuLbvh's build and refit over any Boxes (lbvh_steps.h), for .cu files: gpu_lbvh.cu instantiates
// them for arrays of boxes, the TLAS's users for boxes computed from the instances.
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
    const LbvhLeafGroups groups{n, leafSize_};
    const uint32_t leaves = groups.LeafCount();
    const size_t positions = NodeCount();
    nodes_.Resize(positions);
    parents_.Resize(positions);
    primOrder_.Resize(n);
    RT_CUDA_CHECK(cudaMemsetAsync(parents_.Data(), 0xff, positions * sizeof(uint32_t), stream));
    if (n == 0) {
        const BvhNode empty{vec3(kInfinity), 0, vec3(-kInfinity), 0};
        const BvhNode host[2] = {empty, empty};  // as the CPU build leaves an empty tree
        RT_CUDA_CHECK(
            cudaMemcpyAsync(nodes_.Data(), host, sizeof(host), cudaMemcpyHostToDevice, stream));
        RT_CUDA_CHECK(cudaStreamSynchronize(stream));
        return;
    }
    RT_CUDA_CHECK(cudaMemsetAsync(nodes_.Data() + 1, 0, sizeof(BvhNode), stream));
    codes_.Resize(n);
    sortedCodes_.Resize(n);
    indices_.Resize(n);
    centroidBounds_.Resize(1);
    positionOf_.Resize(std::max(leaves - 1, 1u));
    arrivals_.Resize(positions);

    // The sort ping-pongs between the two arrays of each pair (CUB's double buffer), which
    // spares the scratch a copy of both.
    cub::DoubleBuffer<uint32_t> keys(codes_.Data(), sortedCodes_.Data());
    cub::DoubleBuffer<uint32_t> values(indices_.Data(), primOrder_.Data());
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
                    LbvhMortonCodes<Boxes, OrderedBounds>{bounds, centroidBounds_.Data(),
                                                          codes_.Data(), indices_.Data()},
                    stream);
    RT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(scratch_.Data(), sortBytes, keys, values, int(n),
                                                  0, 30, stream));
    // The sorted arrays are wherever the last pass left them: name them sortedCodes_ and
    // primOrder_ (the other two are rewritten next build).
    if (keys.Current() != sortedCodes_.Data()) std::swap(codes_, sortedCodes_);
    if (values.Current() != primOrder_.Data()) std::swap(indices_, primOrder_);
    if (leaves == 1) {
        ParallelForCuda(0, 1, LbvhRootLeaf<Boxes>{bounds, primOrder_.Data(), n, nodes_.Data()},
                        stream);
        RT_CUDA_CHECK(cudaStreamSynchronize(stream));
        return;
    }
    // Karras's nodes over the leaves' codes: the sorted codes themselves for one primitive per
    // leaf, else every leafSize-th of them, gathered into the free codes_ array.
    const uint32_t* leafCodes = sortedCodes_.Data();
    if (leafSize_ > 1) {
        ParallelForCuda(0, leaves, LbvhLeafCodes{sortedCodes_.Data(), groups, codes_.Data()},
                        stream);
        leafCodes = codes_.Data();
    }
    ParallelForCuda(0, leaves - 1,
                    LbvhKarrasNodes<Boxes>{leafCodes, groups, primOrder_.Data(), bounds,
                                           nodes_.Data(), positionOf_.Data()},
                    stream);
    ParallelForCuda(0, leaves - 1,
                    LbvhLinkNodes{positionOf_.Data(), nodes_.Data(), parents_.Data()}, stream);
    BoundsBottomUp(stream);
}

template <class Boxes>
void GpuLbvh::RefitOver(Boxes bounds, cudaStream_t stream) {
    if (count_ == 0) return;
    if (count_ <= leafSize_) {
        ParallelForCuda(0, 1, LbvhRootLeaf<Boxes>{bounds, primOrder_.Data(), count_, nodes_.Data()},
                        stream);
        return;
    }
    ParallelForCuda(0, NodeCount() - 2,
                    LbvhRefitLeaves<Boxes>{bounds, primOrder_.Data(), nodes_.Data()}, stream);
    BoundsBottomUp(stream);
}

}  // namespace rtrt
