#pragma once
// GpuLbvh's build and refit over any Boxes (lbvh_steps.h), for .cu files: gpu_lbvh.cu instantiates
// them for arrays of boxes, the TLAS's users for boxes computed from the instances.
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>

#include <cub/cub.cuh>
#include <utility>

#include "engine/bvh/build/gpu_lbvh.h"
#include "engine/bvh/build/lbvh_steps.h"
#include "engine/core/parallel_for_cuda.h"

namespace rtrt {

struct LbvhMergeBoxes {
    __device__ Aabb operator()(const Aabb& a, const Aabb& b) const {
        Aabb r = a;
        r.Grow(b);
        return r;
    }
};

// Primitive i's centroid as a box, read straight from its bounds by the reduction (no array).
template <class Boxes>
struct LbvhCentroidBox {
    Boxes boxes;
    __device__ Aabb operator()(uint32_t i) const {
        const vec3 c = Aabb(boxes[i]).Centroid();
        return {c, c};
    }
};

template <class Boxes>
void GpuLbvh::BuildOver(Boxes bounds, uint32_t n, cudaStream_t stream) {
    count_ = n;
    const size_t positions = std::max<size_t>(2, 2 * size_t(n));
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
    positionOf_.Resize(n);
    arrivals_.Resize(positions);

    const auto centroids = thrust::make_transform_iterator(thrust::make_counting_iterator(0u),
                                                           LbvhCentroidBox<Boxes>{bounds});
    // The sort ping-pongs between the two arrays of each pair (CUB's double buffer), which
    // spares the scratch a copy of both.
    cub::DoubleBuffer<uint32_t> keys(codes_.Data(), sortedCodes_.Data());
    cub::DoubleBuffer<uint32_t> values(indices_.Data(), primOrder_.Data());
    // CUB needs scratch memory: ask for the largest of the reduce's and the sort's.
    size_t reduceBytes = 0, sortBytes = 0;
    RT_CUDA_CHECK(cub::DeviceReduce::Reduce(nullptr, reduceBytes, centroids, centroidBounds_.Data(),
                                            int(n), LbvhMergeBoxes(), Aabb(), stream));
    RT_CUDA_CHECK(
        cub::DeviceRadixSort::SortPairs(nullptr, sortBytes, keys, values, int(n), 0, 30, stream));
    const size_t scratchBytes = std::max(reduceBytes, sortBytes);
    if (scratch_.Size() < scratchBytes) scratch_.Resize(scratchBytes);
    RT_CUDA_CHECK(cub::DeviceReduce::Reduce(scratch_.Data(), reduceBytes, centroids,
                                            centroidBounds_.Data(), int(n), LbvhMergeBoxes(),
                                            Aabb(), stream));
    ParallelForCuda(
        0, n,
        LbvhMortonCodes<Boxes>{bounds, centroidBounds_.Data(), codes_.Data(), indices_.Data()},
        stream);
    RT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(scratch_.Data(), sortBytes, keys, values, int(n),
                                                  0, 30, stream));
    // The sorted arrays are wherever the last pass left them: name them sortedCodes_ and
    // primOrder_ (the other two are rewritten next build).
    if (keys.Current() != sortedCodes_.Data()) std::swap(codes_, sortedCodes_);
    if (values.Current() != primOrder_.Data()) std::swap(indices_, primOrder_);
    if (n == 1) {
        ParallelForCuda(0, 1, LbvhRootLeaf<Boxes>{bounds, primOrder_.Data(), nodes_.Data()},
                        stream);
        RT_CUDA_CHECK(cudaStreamSynchronize(stream));
        return;
    }
    ParallelForCuda(0, n - 1,
                    LbvhKarrasNodes<Boxes>{sortedCodes_.Data(), n, primOrder_.Data(), bounds,
                                           nodes_.Data(), positionOf_.Data()},
                    stream);
    ParallelForCuda(0, n - 1, LbvhLinkNodes{positionOf_.Data(), nodes_.Data(), parents_.Data()},
                    stream);
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
