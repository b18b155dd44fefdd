#pragma once
// The LBVH built on the GPU (CUDA) over primitive boxes, for the deforming BLASes: the same steps
// and the same tree as BuildLbvh on the CPU (lbvh.h) — centroid bounds, 30-bit Morton codes, a
// stable CUB radix sort (equal codes keep input order, as the CPU's (code, index) sort), Karras
// 2012 nodes in parallel, bounds bottom-up with a mark on each node (lbvh_steps.h). All arrays
// stay on the device; the build's temporary arrays share memory where their lifetimes allow (see
// the members). The TLAS has its own, leaner form of the same build (gpu_tlas.h).
//
// The centroid bounds come from a reduction of order-preserving integer keys with atomic minima
// (exact in any order, so the Morton codes equal the CPU's) rather than CUB's reduce, whose scratch
// holds a partial box per block it could launch: about 95 KB at any count, which at 1,000 instances
// was over a third of the TLAS's memory.
#include <cuda_runtime.h>

#include "engine/bvh/build/lbvh.h"
#include "engine/bvh/build/ordered_bounds.h"
#include "engine/core/device_buffer.h"

namespace rtrt {

class GpuLbvh {
  public:
    // Builds over n primitive boxes in device memory; the arrays are reused across frames.
    void Build(const Aabb* deviceBounds, uint32_t n, cudaStream_t stream = 0);
    // Refit after the boxes moved (same n, same order of primitives).
    void Refit(const Aabb* deviceBounds, cudaStream_t stream = 0);
    // The same over boxes read through Boxes (lbvh_steps.h), such as boxes computed where the
    // build reads them, which then keeps no array of them. Defined in gpu_lbvh.cuh.
    template <class Boxes>
    void BuildOver(Boxes boxes, uint32_t n, cudaStream_t stream = 0);
    template <class Boxes>
    void RefitOver(Boxes boxes, cudaStream_t stream = 0);

    const BvhNode* Nodes() const { return nodes_.Data(); }
    const uint32_t* PrimOrder() const { return primOrder_.Data(); }
    const uint32_t* Parents() const { return parents_.Data(); }
    uint32_t Count() const { return count_; }
    // The device memory the tree and its build keep between frames (CUB's scratch included).
    size_t DeviceBytes() const;
    // Copies the tree to the host, for tests and for comparison with the CPU build.
    Lbvh Download() const;

  private:
    void BoundsBottomUp(cudaStream_t stream);

    uint32_t count_ = 0;
    DeviceBuffer<BvhNode> nodes_;
    DeviceBuffer<uint32_t> primOrder_, parents_;
    // The sort's second array of primitive indices. The sort's keys (Morton codes) are kept in
    // parents_, two halves of n, until the parent links are written.
    DeviceBuffer<uint32_t> spareIndices_;
    DeviceBuffer<OrderedBounds> centroidBounds_;
    DeviceBuffer<unsigned char> scratch_;  // CUB's temporary storage
};

}  // namespace rtrt
