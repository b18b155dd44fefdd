#include <cub/cub.cuh>

#include "engine/bvh/build/gpu_lbvh.h"
#include "engine/bvh/build/morton.h"

namespace rtrt {
namespace {

constexpr uint32_t kNoParent = UINT32_MAX;
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

__global__ void MortonKernel(const Aabb* bounds, uint32_t n, const Aabb* centroidBounds,
                             uint32_t* codes, uint32_t* indices) {
    const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    codes[i] = MortonCode(bounds[i].Centroid(), *centroidBounds);
    indices[i] = i;
}

__device__ BvhNode LeafNode(const Aabb& b, uint32_t slot) {
    BvhNode node;
    node.SetBounds(b);
    node.leftFirst = slot;
    node.primCount = 1;
    return node;
}

__global__ void KarrasKernel(const uint32_t* codes, uint32_t n, const uint32_t* primOrder,
                             const Aabb* bounds, BvhNode* nodes, uint32_t* positionOf) {
    const uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
    if (k + 1 >= n) return;
    const KarrasNode range = KarrasInternalNode(codes, n, k);
    const uint32_t pair = 2 + 2 * k;
    if (range.split == range.first)
        nodes[pair] = LeafNode(bounds[primOrder[range.split]], range.split);
    else
        positionOf[range.split] = pair;
    if (range.split + 1 == range.last)
        nodes[pair + 1] = LeafNode(bounds[primOrder[range.split + 1]], range.split + 1);
    else
        positionOf[range.split + 1] = pair + 1;
}

__global__ void LinkKernel(uint32_t n, const uint32_t* positionOf, BvhNode* nodes,
                           uint32_t* parents) {
    const uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
    if (k + 1 >= n) return;
    const uint32_t position = k == 0 ? 0 : positionOf[k];
    const uint32_t pair = 2 + 2 * k;
    nodes[position].leftFirst = pair;
    nodes[position].primCount = 0;
    parents[pair] = parents[pair + 1] = position;
}

__global__ void RootLeafKernel(const Aabb* bounds, const uint32_t* primOrder, BvhNode* nodes,
                               uint32_t* parents) {
    nodes[0] = LeafNode(bounds[primOrder[0]], 0);
    parents[0] = kNoParent;
}

__global__ void RefitLeavesKernel(const Aabb* bounds, const uint32_t* primOrder, uint32_t positions,
                                  BvhNode* nodes) {
    const uint32_t p = blockIdx.x * blockDim.x + threadIdx.x + 2;
    if (p >= positions || !nodes[p].IsLeaf()) return;
    nodes[p].SetBounds(bounds[primOrder[nodes[p].leftFirst]]);
}

// Reads a node that another thread may just have written (bypasses the incoherent L1).
__device__ Aabb LoadBounds(const BvhNode* node) {
    const float4* raw = reinterpret_cast<const float4*>(node);
    const float4 lo = __ldcg(raw), hi = __ldcg(raw + 1);
    return {vec3(lo.x, lo.y, lo.z), vec3(hi.x, hi.y, hi.z)};
}

__global__ void BoundsKernel(uint32_t positions, const uint32_t* parents, BvhNode* nodes,
                             uint32_t* arrivals) {
    const uint32_t leaf = blockIdx.x * blockDim.x + threadIdx.x + 2;
    if (leaf >= positions || !nodes[leaf].IsLeaf()) return;
    uint32_t p = parents[leaf];
    while (p != kNoParent) {
        __threadfence();  // this thread's writes below p are visible before it signals
        if (atomicAdd(&arrivals[p], 1u) == 0) return;  // the sibling's thread finishes p
        const uint32_t left = nodes[p].leftFirst;
        Aabb b = LoadBounds(&nodes[left]);
        b.Grow(LoadBounds(&nodes[left + 1]));
        nodes[p].boundsMin = b.min;
        nodes[p].boundsMax = b.max;
        p = parents[p];
    }
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
    MortonKernel<<<Blocks(n), kBlock, 0, stream>>>(bounds, n, centroidBounds_.Data(), codes_.Data(),
                                                   indices_.Data());
    RT_CUDA_CHECK_LAUNCH();
    RT_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(scratch_.Data(), sortBytes, codes_.Data(),
                                                  sortedCodes_.Data(), indices_.Data(),
                                                  primOrder_.Data(), int(n), 0, 30, stream));
    if (n == 1) {
        RootLeafKernel<<<1, 1, 0, stream>>>(bounds, primOrder_.Data(), nodes_.Data(),
                                            parents_.Data());
        RT_CUDA_CHECK_LAUNCH();
        RT_CUDA_CHECK(cudaStreamSynchronize(stream));
        return;
    }
    KarrasKernel<<<Blocks(n - 1), kBlock, 0, stream>>>(sortedCodes_.Data(), n, primOrder_.Data(),
                                                       bounds, nodes_.Data(), positionOf_.Data());
    RT_CUDA_CHECK_LAUNCH();
    LinkKernel<<<Blocks(n - 1), kBlock, 0, stream>>>(n, positionOf_.Data(), nodes_.Data(),
                                                     parents_.Data());
    RT_CUDA_CHECK_LAUNCH();
    BoundsBottomUp(stream);
}

void GpuLbvh::Refit(const Aabb* bounds, cudaStream_t stream) {
    if (count_ == 0) return;
    if (count_ == 1) {
        RootLeafKernel<<<1, 1, 0, stream>>>(bounds, primOrder_.Data(), nodes_.Data(),
                                            parents_.Data());
        RT_CUDA_CHECK_LAUNCH();
        return;
    }
    const uint32_t positions = 2 * count_;
    RefitLeavesKernel<<<Blocks(positions), kBlock, 0, stream>>>(bounds, primOrder_.Data(),
                                                                positions, nodes_.Data());
    RT_CUDA_CHECK_LAUNCH();
    BoundsBottomUp(stream);
}

void GpuLbvh::BoundsBottomUp(cudaStream_t stream) {
    const uint32_t positions = 2 * count_;
    RT_CUDA_CHECK(cudaMemsetAsync(arrivals_.Data(), 0, positions * sizeof(uint32_t), stream));
    BoundsKernel<<<Blocks(positions), kBlock, 0, stream>>>(positions, parents_.Data(),
                                                           nodes_.Data(), arrivals_.Data());
    RT_CUDA_CHECK_LAUNCH();
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
