#include <cub/cub.cuh>

#include "engine/bvh/build/gpu_lbvh.h"
#include "engine/bvh/build/lbvh_steps.h"
#include "engine/core/parallel_for_cuda.h"

namespace rtrt {
namespace {

constexpr int kBlock = 256;

uint32_t Blocks(uint32_t n) { return (n + kBlock - 1) / kBlock; }

struct MergeBoxes {
    __device__ Aabb operator()(const Aabb& a, const Aabb& b) const {
        Aabb r = a;
        r.Grow(b);
        return r;
    }
};

__global__ void CentroidsKernel(const Aabb* bounds, uint32_t n, Aabb* centroids) {
    const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    const vec3 c = bounds[i].Centroid();
    centroids[i] = {c, c};
}

}  // namespace

void GpuLbvh::Build(const Aabb* bounds, uint32_t n, cudaStream_t stream) {
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
    centroids_.Resize(n);
    centroidBounds_.Resize(1);
    positionOf_.Resize(n);
    arrivals_.Resize(positions);

    CentroidsKernel<<<Blocks(n), kBlock, 0, stream>>>(bounds, n, centroids_.Data());
    RT_CUDA_CHECK_LAUNCH();
    // CUB needs scratch memory: ask for the largest of the reduce's and the sort's.
    size_t reduceBytes = 0, sortBytes = 0;
    RT_CUDA_CHECK(cub::DeviceReduce::Reduce(nullptr, reduceBytes, centroids_.Data(),
                                            centroidBounds_.Data(), int(n), MergeBoxes(), Aabb(),
                                            stream));
    RT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, sortBytes, codes_.Data(),
                                                  sortedCodes_.Data(), indices_.Data(),
                                                  primOrder_.Data(), int(n), 0, 30, stream));
    const size_t scratchBytes = std::max(reduceBytes, sortBytes);
    if (scratch_.Size() < scratchBytes) scratch_.Resize(scratchBytes);
    RT_CUDA_CHECK(cub::DeviceReduce::Reduce(scratch_.Data(), reduceBytes, centroids_.Data(),
                                            centroidBounds_.Data(), int(n), MergeBoxes(), Aabb(),
                                            stream));
    ParallelForCuda(0, n,
                    LbvhMortonCodes{bounds, centroidBounds_.Data(), codes_.Data(), indices_.Data()},
                    stream);
    RT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(scratch_.Data(), sortBytes, codes_.Data(),
                                                  sortedCodes_.Data(), indices_.Data(),
                                                  primOrder_.Data(), int(n), 0, 30, stream));
    if (n == 1) {
        ParallelForCuda(0, 1, LbvhRootLeaf{bounds, primOrder_.Data(), nodes_.Data()}, stream);
        RT_CUDA_CHECK(cudaStreamSynchronize(stream));
        return;
    }
    ParallelForCuda(0, n - 1,
                    LbvhKarrasNodes{sortedCodes_.Data(), n, primOrder_.Data(), bounds,
                                    nodes_.Data(), positionOf_.Data()},
                    stream);
    ParallelForCuda(0, n - 1, LbvhLinkNodes{positionOf_.Data(), nodes_.Data(), parents_.Data()},
                    stream);
    BoundsBottomUp(stream);
}

void GpuLbvh::Refit(const Aabb* bounds, cudaStream_t stream) {
    if (count_ == 0) return;
    if (count_ == 1) {
        ParallelForCuda(0, 1, LbvhRootLeaf{bounds, primOrder_.Data(), nodes_.Data()}, stream);
        return;
    }
    const uint32_t positions = 2 * count_;
    ParallelForCuda(0, positions - 2, LbvhRefitLeaves{bounds, primOrder_.Data(), nodes_.Data()},
                    stream);
    BoundsBottomUp(stream);
}

void GpuLbvh::BoundsBottomUp(cudaStream_t stream) {
    const uint32_t positions = 2 * count_;
    RT_CUDA_CHECK(cudaMemsetAsync(arrivals_.Data(), 0, positions * sizeof(uint32_t), stream));
    ParallelForCuda(0, positions - 2,
                    LbvhBoundsBottomUp{parents_.Data(), nodes_.Data(), arrivals_.Data()}, stream);
}

Lbvh GpuLbvh::Download() const {
    RT_CUDA_CHECK(cudaDeviceSynchronize());
    Lbvh host;
    host.nodes.resize(nodes_.Size());
    host.parents.resize(parents_.Size());
    host.primOrder.resize(count_);
    nodes_.Download(host.nodes);
    parents_.Download(host.parents);
    if (count_) primOrder_.Download(host.primOrder);
    return host;
}

}  // namespace rtrt
