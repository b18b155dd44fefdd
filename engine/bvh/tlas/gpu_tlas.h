#pragma once
// The runtime's TLAS on the GPU (CUDA): the LBVH of BuildLbvh(…, LbvhLeaves::kPrimitiveIds), bit
// for bit, over the instances' world boxes, built or refit in place every frame. It keeps nothing
// but its nodes, two per instance (a pair per Karras node, 64 bytes):
// - the parent links it needs to refit are one per pair, so one per instance; they live in the
//   records' TLAS words (instance.h) rather than in an array of their own;
// - the bottom-up pass marks the nodes it reaches (lbvh_steps.h) instead of keeping counters;
// - the leaves name their instances (tlas.h), so there is no leaf order to keep;
// - the build's temporaries (Morton codes, sort indices, CUB's scratch, the centroids' bounds)
//   live in the node array before the nodes are written, and the sorted codes and order in the
//   records' TLAS words while the nodes are written from them.
#include <cuda_runtime.h>

#include "engine/bvh/layout/bvh_node.h"
#include "engine/bvh/tlas/tlas.h"
#include "engine/core/device_buffer.h"

namespace rtrt {

// What the tree reads of each BLAS, by BLAS id, in device memory: its box and, where given, its
// outline (blas_outline.h).
struct GpuBlasBounds {
    GpuBlasBounds(const Aabb* boxes, const BlasOutline* outlines = nullptr)  // NOLINT: boxes alone
        : boxes(boxes), outlines(outlines) {}
    const Aabb* boxes;
    const BlasOutline* outlines;
};

class GpuTlas {
  public:
    // Builds over n records (InstanceWorldBox of each), writing their TLAS words.
    void Build(Instance* records, GpuBlasBounds blas, uint32_t n, cudaStream_t stream = 0);
    // Refit after the records moved (same n and the same records, TLAS words as Build left them).
    void Refit(Instance* records, GpuBlasBounds blas, cudaStream_t stream = 0);

    // Takes another GPU's tree over the same n records (its nodeCount nodes, on sourceDevice) in
    // place of a build: a copy queued on `stream` of the current device.
    void CopyFrom(const BvhNode* source, int sourceDevice, uint32_t nodeCount, uint32_t n,
                  cudaStream_t stream = 0);

    const BvhNode* Nodes() const { return nodes_.Data(); }
    uint32_t NodeCount() const { return uint32_t(nodes_.Size()); }
    uint32_t Count() const { return count_; }
    // The device memory the tree and its build keep between frames.
    size_t DeviceBytes() const;
    // Copies the tree to the host, for tests and for comparison with the CPU build.
    Tlas Download() const;

  private:
    uint32_t count_ = 0;
    DeviceBuffer<BvhNode> nodes_;
    // CUB's sort scratch where it does not fit in the node array beside the sort's arrays (only
    // for a few instances).
    DeviceBuffer<unsigned char> scratch_;
};

}  // namespace rtrt
