#pragma once
// The CUDA back end's deforming BLASes: the pools of deform_plan.h in device memory, brought up to
// date by the shared steps (deform_steps.h), one thread per item and one launch per step for all
// of a frame's deformations, rebuilt with the GPU LBVH when the policy says so. Everything is
// queued on the default stream; the SAH costs the policy needs are read a frame late, never
// waited for in the frame that computes them (except by the next Update). For CUDA host code.
#include <cuda_runtime.h>

#include <memory>
#include <span>
#include <vector>

#include "engine/bvh/build/gpu_lbvh.h"
#include "engine/core/device_buffer.h"
#include "engine/render_rt/deform/deform_plan.h"

namespace rtrt {

// Events the deformer records inside a frame, for its stage times.
struct DeformEvents {
    cudaEvent_t vertices, rebuilt, gathered, refit;
};

class CudaDeformer {
  public:
    explicit CudaDeformer(BlasRebuildPolicy policy = {});
    ~CudaDeformer();
    CudaDeformer(const CudaDeformer&) = delete;
    CudaDeformer& operator=(const CudaDeformer&) = delete;

    // Queues the update of the deformations in `changed` and any the scene gained, writing their
    // root boxes into deviceBlasBounds (indexed by BLAS id). Returns true when any BLAS view
    // moved (new deformations): the caller then takes Views() again. The events are recorded
    // whether or not there is work.
    bool Update(const RenderScene& scene, std::span<const uint32_t> changed, Aabb* deviceBlasBounds,
                const DeformEvents& events);
    // The deformed BLASes' views (device pointers), by deformation; the BLAS id is Plan().Slot(d).
    std::vector<BlasView> Views() const;
    // Of the last Update: deformations updated, rebuilt, their triangles.
    uint32_t Deformed() const { return uint32_t(plan_.Jobs().size()); }
    uint32_t Rebuilt() const { return uint32_t(plan_.RebuildJobs().size()); }
    uint64_t Triangles() const { return triangleCount_; }
    const DeformPlan& Plan() const { return plan_; }
    // Waits for the last update's costs and hands them to the policy.
    void CollectCosts();

  private:
    void Admit(const RenderScene& scene);
    DeformJobs Work() const;
    void Rebuild(uint32_t job);

    DeformPlan plan_;
    // Per mesh: its arrays on the device.
    struct MeshArrays {
        DeviceBuffer<vec3> positions, normals, positionDeltas, normalDeltas;
        DeviceBuffer<glm::uvec3> indices;
        DeviceBuffer<vec2> uvs;
        DeviceBuffer<vec3> colors;
        DeviceBuffer<uint32_t> joints;
        DeviceBuffer<float> weights;
    };
    std::vector<std::unique_ptr<MeshArrays>> meshArrays_;
    std::vector<DeformMeshView> meshViews_;
    DeviceBuffer<DeformMeshView> meshes_;
    DeviceBuffer<vec3> positions_;
    DeviceBuffer<uint32_t> normals_;  // packed
    DeviceBuffer<Triangle> triangles_;
    DeviceBuffer<TriangleNormals> triangleNormals_;
    DeviceBuffer<TriangleUvs> triangleUvs_;
    DeviceBuffer<TriangleColors> triangleColors_;  // empty until a mesh with colours comes
    DeviceBuffer<uint32_t> slotTriangle_;
    DeviceBuffer<BvhNode> nodes_;
    DeviceBuffer<uint32_t> parents_;
    // The frame's work: jobs, the items' begins, poses, SAH terms and per-job costs.
    DeviceBuffer<DeformJob> jobs_;
    DeviceBuffer<uint32_t> vertexBegins_, slotBegins_, nodeBegins_;
    DeviceBuffer<Affine> joints_;
    DeviceBuffer<float> weights_, terms_, costs_;
    DeviceBuffer<Aabb> boxes_;
    DeviceBuffer<unsigned char> scratch_;
    GpuLbvh builder_;
    float* costsHost_ = nullptr;  // pinned
    size_t costsCapacity_ = 0;
    cudaEvent_t costsCopied_;
    std::vector<uint32_t> pendingDeformations_;
    std::vector<uint8_t> pendingRebuilt_;
    uint64_t triangleCount_ = 0;
};

}  // namespace rtrt
