#pragma once
// The SAH cost of the GPU TLAS (sah_term.h), summed on the GPU in a fixed order, so that it is
// the same run to run and the rebuild decisions with it, and copied back into pinned memory
// without a synchronous copy: queued after one update, read at the next.
#include <cuda_runtime.h>

#include <cstdint>

#include "engine/bvh/layout/bvh_node.h"
#include "engine/core/device_buffer.h"

namespace rtrt {

class TlasSahCost {
  public:
    TlasSahCost();  // on the current device
    ~TlasSahCost();
    TlasSahCost(const TlasSahCost&) = delete;
    TlasSahCost& operator=(const TlasSahCost&) = delete;

    // Queues on the default stream the cost of the tree over leafCount instances (nodes in the
    // pair layout, 2 leafCount positions); afterRebuild marks it as the cost of a fresh build.
    void Queue(const BvhNode* nodes, uint32_t leafCount, bool afterRebuild);
    // Takes in the queued cost, once its copy has landed; nothing when none is queued.
    void Collect();

    float Last() const { return last_; }        // the latest collected cost
    float Rebuilt() const { return rebuilt_; }  // the latest collected cost of a fresh build

  private:
    int device_ = 0;            // the current device when made
    DeviceBuffer<float> sums_;  // each level's partial sums after the level before's
    float* host_ = nullptr;     // pinned
    cudaEvent_t copied_;
    bool pending_ = false, pendingIsRebuild_ = false;
    float last_ = 0.0f, rebuilt_ = 0.0f;
};

}  // namespace rtrt
