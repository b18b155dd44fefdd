#include "engine/bvh/build/gpu_lbvh.cuh"

namespace rtrt {

template void GpuLbvh::BuildOver<const Aabb*>(const Aabb*, uint32_t, cudaStream_t);
template void GpuLbvh::RefitOver<const Aabb*>(const Aabb*, cudaStream_t);

void GpuLbvh::Build(const Aabb* bounds, uint32_t n, cudaStream_t stream) {
    BuildOver(bounds, n, stream);
}

void GpuLbvh::Refit(const Aabb* bounds, cudaStream_t stream) { RefitOver(bounds, stream); }

void GpuLbvh::BoundsBottomUp(cudaStream_t stream) {
    ParallelForCuda(0, 2 * count_ - 2,
                    LbvhBoundsBottomUp<LbvhPositionParents>{{parents_.Data()}, nodes_.Data()},
                    stream);
}

size_t GpuLbvh::DeviceBytes() const {
    auto bytes = [](const auto& buffer) { return buffer.Size() * sizeof(*buffer.Data()); };
    return bytes(nodes_) + bytes(primOrder_) + bytes(parents_) + bytes(spareIndices_) +
           bytes(centroidBounds_) + bytes(scratch_);
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
