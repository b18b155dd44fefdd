#include "engine/bvh/build/sah_term.h"
#include "engine/core/cuda_check.h"
#include "engine/render_rt/cuda/tlas_sah_cost.h"

namespace rtrt {
namespace {

constexpr uint32_t kBlock = 256;
constexpr uint32_t kSumPerThread = 8;
constexpr uint32_t kSumSpan = kBlock * kSumPerThread;  // the values one block sums
uint32_t SumBlocks(uint32_t n) { return (n + kSumSpan - 1) / kSumSpan; }

// Each node's term, read where the sum needs it.
struct SahTerms {
    const BvhNode* nodes;
    __device__ float operator[](uint32_t position) const { return SahNodeTerm(nodes, position); }
};

// Block b sums values [b kSumSpan, (b + 1) kSumSpan) in a fixed order (each thread its strided
// share, then a tree in shared memory); only one partial sum per block is kept, not a term per
// node.
template <class Values>
__global__ void BlockSumsKernel(Values values, uint32_t n, float* sums) {
    __shared__ float partial[kBlock];
    const uint32_t first = blockIdx.x * kSumSpan + threadIdx.x;
    float s = 0.0f;
    for (uint32_t k = 0; k < kSumPerThread; ++k)
        if (first + k * kBlock < n) s += values[first + k * kBlock];
    partial[threadIdx.x] = s;
    __syncthreads();
    for (uint32_t half = kBlock / 2; half > 0; half /= 2) {
        if (threadIdx.x < half) partial[threadIdx.x] += partial[threadIdx.x + half];
        __syncthreads();
    }
    if (threadIdx.x == 0) sums[blockIdx.x] = partial[0];
}

}  // namespace

TlasSahCost::TlasSahCost() {
    RT_CUDA_CHECK(cudaGetDevice(&device_));
    RT_CUDA_CHECK(cudaEventCreate(&copied_));
    RT_CUDA_CHECK(cudaMallocHost(&host_, sizeof(float)));
}

// Frees on the device it was made on (an owner's device guard has ended by the time its members
// are destroyed), without throwing.
TlasSahCost::~TlasSahCost() {
    int current = device_;
    cudaGetDevice(&current);
    if (current != device_) cudaSetDevice(device_);
    cudaEventDestroy(copied_);
    cudaFreeHost(host_);
    if (current != device_) cudaSetDevice(current);
}

void TlasSahCost::Queue(const BvhNode* nodes, uint32_t leafCount, bool afterRebuild) {
    uint32_t count = leafCount == 0 ? 2u : 2u * leafCount;
    size_t partials = 0;
    for (uint32_t c = count; c > 1 || partials == 0; c = SumBlocks(c)) partials += SumBlocks(c);
    if (sums_.Size() < partials) sums_.Resize(partials);
    float* sums = sums_.Data();
    uint32_t blocks = SumBlocks(count);
    BlockSumsKernel<<<blocks, kBlock>>>(SahTerms{nodes}, count, sums);
    RT_CUDA_CHECK_LAUNCH();
    while (blocks > 1) {
        const float* previous = sums;
        sums += blocks;
        count = blocks;
        blocks = SumBlocks(count);
        BlockSumsKernel<<<blocks, kBlock>>>(previous, count, sums);
        RT_CUDA_CHECK_LAUNCH();
    }
    RT_CUDA_CHECK(cudaMemcpyAsync(host_, sums, sizeof(float), cudaMemcpyDeviceToHost));
    RT_CUDA_CHECK(cudaEventRecord(copied_));
    pending_ = true;
    pendingIsRebuild_ = afterRebuild;
}

void TlasSahCost::Collect() {
    if (!pending_) return;
    RT_CUDA_CHECK(cudaEventSynchronize(copied_));
    last_ = *host_;
    if (pendingIsRebuild_) rebuilt_ = last_;
    pending_ = false;
}

}  // namespace rtrt
