#include <algorithm>

#include "engine/bvh/build/gpu_lbvh.cuh"
#include "engine/bvh/build/lbvh_steps.h"
#include "engine/bvh/tlas/gpu_tlas.h"

namespace rtrt {
namespace {

// Which TLAS word of a record holds what: the sorted order (leaf s's instance) until the nodes
// are written, then the parent link of pair s; the sorted Morton codes while the nodes are
// written.
constexpr int kOrderWord = 0, kParentWord = 0, kCodeWord = 1;

// Word w of every record's TLAS words, read and written as one array.
struct TlasWords {
    Instance* records;
    int word;
    RT_HD uint32_t& operator[](size_t i) const { return records[i].tlasWords[word]; }
};

// The order of a tree of one instance.
struct FirstInstance {
    RT_HD uint32_t operator[](size_t) const { return 0; }
};

using PairParents = LbvhPairParents<TlasWords>;

// The sorted codes and order move into the records, freeing the node array for the nodes.
struct StoreSorted {
    const uint32_t* codes;
    const uint32_t* order;
    Instance* records;
    RT_HD void operator()(size_t i) const {
        records[i].tlasWords[kOrderWord] = order[i];
        records[i].tlasWords[kCodeWord] = codes[i];
    }
};

constexpr size_t kScratchAlignment = 256;  // as cudaMalloc's

void BoundsBottomUp(Instance* records, BvhNode* nodes, uint32_t n, cudaStream_t stream) {
    ParallelForCuda(0, 2 * n - 2,
                    LbvhBoundsBottomUp<PairParents>{{TlasWords{records, kParentWord}}, nodes},
                    stream);
}

}  // namespace

void GpuTlas::Build(Instance* records, GpuBlasBounds blas, uint32_t n, cudaStream_t stream) {
    count_ = n;
    nodes_.Resize(std::max<size_t>(2, 2 * size_t(n)));
    BvhNode* const nodes = nodes_.Data();
    const InstanceWorldBoxes boxes{records, blas.boxes, blas.outlines};
    if (n == 0) {
        const BvhNode empty{vec3(kInfinity), 0, vec3(-kInfinity), 0};
        const BvhNode host[2] = {empty, empty};  // as the CPU build leaves an empty tree
        RT_CUDA_CHECK(cudaMemcpyAsync(nodes, host, sizeof(host), cudaMemcpyHostToDevice, stream));
        RT_CUDA_CHECK(cudaStreamSynchronize(stream));
        return;
    }
    RT_CUDA_CHECK(cudaMemsetAsync(nodes + 1, 0, sizeof(BvhNode), stream));
    if (n == 1) {
        scratch_.Resize(0);
        ParallelForCuda(0, 1,
                        LbvhRootLeaf<InstanceWorldBoxes, FirstInstance>{
                            boxes, {}, nodes, LbvhLeaves::kPrimitiveIds},
                        stream);
        return;
    }

    // The node array before the nodes: the centroids' bounds at position 1 (which the tree
    // leaves unused), then the sort's keys and values (two arrays each: CUB's double buffer),
    // then CUB's scratch where it fits.
    static_assert(sizeof(OrderedBounds) <= sizeof(BvhNode));
    OrderedBounds* const centroidBounds = reinterpret_cast<OrderedBounds*>(nodes + 1);
    uint32_t* const words = reinterpret_cast<uint32_t*>(nodes + 2);
    cub::DoubleBuffer<uint32_t> keys(words, words + n);
    cub::DoubleBuffer<uint32_t> values(words + 2 * size_t(n), words + 3 * size_t(n));
    size_t sortBytes = 0;
    RT_CUDA_CHECK(
        cub::DeviceRadixSort::SortPairs(nullptr, sortBytes, keys, values, int(n), 0, 30, stream));
    const size_t total = nodes_.Size() * sizeof(BvhNode);
    const size_t offset =
        (2 * sizeof(BvhNode) + 4 * size_t(n) * sizeof(uint32_t) + kScratchAlignment - 1) /
        kScratchAlignment * kScratchAlignment;
    void* scratch = nullptr;
    if (offset + sortBytes <= total) {
        scratch_.Resize(0);
        scratch = reinterpret_cast<unsigned char*>(nodes) + offset;
    } else {
        if (scratch_.Size() < sortBytes) scratch_.Resize(sortBytes);
        scratch = scratch_.Data();
    }

    RT_CUDA_CHECK(cudaMemsetAsync(centroidBounds, 0xff, sizeof(OrderedBounds), stream));
    constexpr uint32_t kBlock = 256, kMaxBlocks = 1024;  // a few per SM: few atomics
    const uint32_t blocks = std::min((n + kBlock - 1) / kBlock, kMaxBlocks);
    LbvhCentroidBoundsKernel<<<blocks, kBlock, 0, stream>>>(boxes, n, centroidBounds);
    RT_CUDA_CHECK_LAUNCH();
    ParallelForCuda(0, n,
                    LbvhMortonCodes<InstanceWorldBoxes, OrderedBounds>{
                        boxes, centroidBounds, keys.Current(), values.Current()},
                    stream);
    RT_CUDA_CHECK(
        cub::DeviceRadixSort::SortPairs(scratch, sortBytes, keys, values, int(n), 0, 30, stream));
    ParallelForCuda(0, n, StoreSorted{keys.Current(), values.Current(), records}, stream);

    // The temporaries are dead: node 1 takes the CPU build's value, the nodes the rest.
    RT_CUDA_CHECK(cudaMemsetAsync(nodes + 1, 0, sizeof(BvhNode), stream));
    ParallelForCuda(0, n - 1,
                    LbvhKarrasNodes<InstanceWorldBoxes, TlasWords, TlasWords>{
                        TlasWords{records, kCodeWord}, n, TlasWords{records, kOrderWord}, boxes,
                        nodes, LbvhLeaves::kPrimitiveIds},
                    stream);
    // The order is read (the leaves hold it): its words take the parent links.
    ParallelForCuda(0, 2 * n, LbvhLinkNodes<PairParents>{nodes, {TlasWords{records, kParentWord}}},
                    stream);
    BoundsBottomUp(records, nodes, n, stream);
}

void GpuTlas::Refit(Instance* records, GpuBlasBounds blas, cudaStream_t stream) {
    const InstanceWorldBoxes boxes{records, blas.boxes, blas.outlines};
    BvhNode* const nodes = nodes_.Data();
    if (count_ == 0) return;
    if (count_ == 1) {
        ParallelForCuda(0, 1,
                        LbvhRootLeaf<InstanceWorldBoxes, FirstInstance>{
                            boxes, {}, nodes, LbvhLeaves::kPrimitiveIds},
                        stream);
        return;
    }
    ParallelForCuda(
        0, 2 * count_ - 2,
        LbvhRefitLeaves<InstanceWorldBoxes>{boxes, nullptr, nodes, LbvhLeaves::kPrimitiveIds},
        stream);
    BoundsBottomUp(records, nodes, count_, stream);
}

void GpuTlas::CopyFrom(const BvhNode* source, int sourceDevice, uint32_t nodeCount, uint32_t n,
                       cudaStream_t stream) {
    int device = 0;
    RT_CUDA_CHECK(cudaGetDevice(&device));
    nodes_.Resize(nodeCount);
    count_ = n;
    if (nodeCount > 0)
        RT_CUDA_CHECK(cudaMemcpyPeerAsync(nodes_.Data(), device, source, sourceDevice,
                                          nodeCount * sizeof(BvhNode), stream));
}

size_t GpuTlas::DeviceBytes() const { return nodes_.Size() * sizeof(BvhNode) + scratch_.Size(); }

Tlas GpuTlas::Download() const {
    RT_CUDA_CHECK(cudaDeviceSynchronize());
    Tlas host;
    host.nodes.resize(nodes_.Size());
    nodes_.Download(host.nodes);
    return host;
}

}  // namespace rtrt
