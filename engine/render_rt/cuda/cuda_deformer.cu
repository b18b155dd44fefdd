#include <cub/cub.cuh>

#include "engine/core/parallel_for_cuda.h"
#include "engine/render_rt/cuda/cuda_deformer.h"

namespace rtrt {
namespace {

template <typename T>
void UploadAsync(DeviceBuffer<T>& buffer, std::span<const T> host) {
    if (buffer.Size() < host.size()) buffer.Resize(host.size());
    if (!host.empty())
        RT_CUDA_CHECK(
            cudaMemcpyAsync(buffer.Data(), host.data(), host.size_bytes(), cudaMemcpyHostToDevice));
}

template <typename T>
void CopyInto(DeviceBuffer<T>& buffer, size_t offset, std::span<const T> host) {
    if (!host.empty())
        RT_CUDA_CHECK(cudaMemcpy(buffer.Data() + offset, host.data(), host.size_bytes(),
                                 cudaMemcpyHostToDevice));
}

template <typename T>
const T* OrNull(const DeviceBuffer<T>& b) {
    return b.Size() ? b.Data() : nullptr;
}

}  // namespace

CudaDeformer::CudaDeformer(BlasRebuildPolicy policy) : plan_(policy) {
    RT_CUDA_CHECK(cudaEventCreateWithFlags(&costsCopied_, cudaEventDisableTiming));
}

CudaDeformer::~CudaDeformer() {
    cudaEventDestroy(costsCopied_);
    if (costsHost_) cudaFreeHost(costsHost_);
}

void CudaDeformer::Admit(const RenderScene& scene) {
    const std::vector<DeformSlotInit> added = plan_.Admit(scene);
    if (meshArrays_.size() < plan_.MeshCount()) {
        for (size_t m = meshArrays_.size(); m < plan_.MeshCount(); ++m) {
            const DeformableMesh& mesh = *scene.deformableMeshes[m];
            auto a = std::make_unique<MeshArrays>();
            a->positions.Upload(mesh.rest.positions);
            a->normals.Upload(mesh.rest.normals);
            a->indices.Upload(mesh.rest.indices);
            a->uvs.Upload(mesh.rest.uvs);
            a->colors.Upload(mesh.rest.colors);
            a->joints.Upload(mesh.joints);
            a->weights.Upload(mesh.weights);
            a->positionDeltas.Upload(mesh.positionDeltas);
            a->normalDeltas.Upload(mesh.normalDeltas);
            DeformMeshView v = HostMeshView(mesh);
            v.positions = a->positions.Data();
            v.normals = OrNull(a->normals);
            v.indices = a->indices.Data();
            v.uvs = OrNull(a->uvs);
            v.colors = OrNull(a->colors);
            v.joints = OrNull(a->joints);
            v.weights = OrNull(a->weights);
            v.positionDeltas = OrNull(a->positionDeltas);
            v.normalDeltas = OrNull(a->normalDeltas);
            meshViews_.push_back(v);
            meshArrays_.push_back(std::move(a));
        }
        meshes_.Upload(meshViews_);
    }
    if (added.empty()) return;
    RT_CUDA_CHECK(cudaDeviceSynchronize());  // the pools may move: nothing may be reading them
    positions_.GrowTo(plan_.VertexTotal());
    normals_.GrowTo(plan_.VertexTotal());
    triangles_.GrowTo(plan_.SlotTotal());
    triangleNormals_.GrowTo(plan_.SlotTotal());
    triangleUvs_.GrowTo(plan_.SlotTotal());
    if (triangleColors_.Size() > 0 || AnyColors(added)) triangleColors_.GrowTo(plan_.SlotTotal());
    slotTriangle_.GrowTo(plan_.SlotTotal());
    nodes_.GrowTo(plan_.NodeTotal());
    parents_.GrowTo(plan_.NodeTotal());
    for (const DeformSlotInit& init : added) {
        const DeformJob& at = plan_.Slot(init.deformation);
        CopyInto(nodes_, at.nodeOffset, std::span<const BvhNode>(init.rest->nodes));
        CopyInto(parents_, at.nodeOffset, std::span<const uint32_t>(init.parents));
        CopyInto(slotTriangle_, at.slotOffset, std::span<const uint32_t>(init.rest->primIds));
        CopyInto(triangleUvs_, at.slotOffset, std::span<const TriangleUvs>(init.rest->uvs));
        CopyInto(triangleColors_, at.slotOffset,
                 std::span<const TriangleColors>(init.rest->colors));
    }
}

DeformJobs CudaDeformer::Work() const {
    DeformPools pools{positions_.Data(),       normals_.Data(),     triangles_.Data(),
                      triangleNormals_.Data(), triangleUvs_.Data(), triangleColors_.Data(),
                      slotTriangle_.Data(),    nodes_.Data(),       parents_.Data()};
    return {jobs_.Data(), uint32_t(plan_.Jobs().size()), meshes_.Data(), pools};
}

std::vector<BlasView> CudaDeformer::Views() const {
    std::vector<BlasView> views;
    for (uint32_t d = 0; d < plan_.DeformationCount(); ++d) {
        const DeformJob& at = plan_.Slot(d);
        const DeformMeshView& mesh = meshViews_[at.mesh];
        BlasView v{};
        v.nodes = nodes_.Data() + at.nodeOffset;
        v.nodes4 = nullptr;
        v.triangles = triangles_.Data() + at.slotOffset;
        v.normals = mesh.normals ? triangleNormals_.Data() + at.slotOffset : nullptr;
        v.spheres = nullptr;
        v.kind = GeometryKind::kTriangles;
        v.primCount = plan_.SlotCount(d);
        v.uvs = mesh.uvs ? triangleUvs_.Data() + at.slotOffset : nullptr;
        v.colors = mesh.colors ? triangleColors_.Data() + at.slotOffset : nullptr;
        views.push_back(v);
    }
    return views;
}

// An LBVH over the deformed triangles replaces the job's tree, queued like the rest.
void CudaDeformer::Rebuild(uint32_t j) {
    const DeformJob& job = plan_.Jobs()[j];
    const DeformMeshView& mesh = meshViews_[job.mesh];
    if (boxes_.Size() < mesh.triangleCount) boxes_.Resize(mesh.triangleCount);
    ParallelForCuda(0, mesh.triangleCount,
                    TriangleBoxesStep{mesh, positions_.Data() + job.vertexOffset, boxes_.Data()});
    builder_.Build(boxes_.Data(), mesh.triangleCount);
    const uint32_t positions = std::max(2u, 2 * mesh.triangleCount);
    RT_CUDA_CHECK(cudaMemcpyAsync(nodes_.Data() + job.nodeOffset, builder_.Nodes(),
                                  positions * sizeof(BvhNode), cudaMemcpyDeviceToDevice));
    RT_CUDA_CHECK(cudaMemcpyAsync(parents_.Data() + job.nodeOffset, builder_.Parents(),
                                  positions * sizeof(uint32_t), cudaMemcpyDeviceToDevice));
    RT_CUDA_CHECK(cudaMemcpyAsync(slotTriangle_.Data() + job.slotOffset, builder_.PrimOrder(),
                                  mesh.triangleCount * sizeof(uint32_t), cudaMemcpyDeviceToDevice));
    plan_.SetNodeCount(j, positions);
}

void CudaDeformer::CollectCosts() {
    if (pendingDeformations_.empty()) return;
    RT_CUDA_CHECK(cudaEventSynchronize(costsCopied_));
    plan_.ReportCosts(pendingDeformations_, pendingRebuilt_,
                      std::span<const float>(costsHost_, pendingDeformations_.size()));
    pendingDeformations_.clear();
}

bool CudaDeformer::Update(const RenderScene& scene, std::span<const uint32_t> changed,
                          Aabb* deviceBlasBounds, const DeformEvents& events) {
    CollectCosts();
    const uint32_t known = plan_.DeformationCount();
    Admit(scene);
    plan_.PlanFrame(scene, changed);
    const uint32_t jobs = uint32_t(plan_.Jobs().size());
    triangleCount_ = 0;
    if (jobs == 0) {
        for (cudaEvent_t e : {events.vertices, events.rebuilt, events.gathered, events.refit})
            RT_CUDA_CHECK(cudaEventRecord(e));
        return plan_.DeformationCount() != known;
    }
    // Poses point into the device copies of the flattened joint matrices and weights.
    UploadAsync(joints_, plan_.JointMatrices());
    UploadAsync(weights_, plan_.MorphWeights());
    for (uint32_t j = 0; j < jobs; ++j) {
        triangleCount_ += plan_.SlotCount(plan_.JobDeformations()[j]);
        DeformJob& job = plan_.MutableJobs()[j];
        job.pose.joints = joints_.Data() + plan_.JointOffset(j);
        job.pose.morphWeights = weights_.Data() + plan_.WeightOffset(j);
    }
    UploadAsync(vertexBegins_, plan_.VertexBegins());
    UploadAsync(slotBegins_, plan_.SlotBegins());
    UploadAsync(jobs_, plan_.Jobs());
    ParallelForCuda(0, plan_.VertexBegins().back(),
                    DeformVerticesStep{Work(), vertexBegins_.Data()});
    RT_CUDA_CHECK(cudaEventRecord(events.vertices));
    for (uint32_t j : plan_.RebuildJobs()) Rebuild(j);
    if (!plan_.RebuildJobs().empty()) UploadAsync(jobs_, plan_.Jobs());  // new node counts
    RT_CUDA_CHECK(cudaEventRecord(events.rebuilt));
    ParallelForCuda(0, plan_.SlotBegins().back(),
                    GatherTrianglesStep{Work(), slotBegins_.Data(), !plan_.RebuildJobs().empty()});
    RT_CUDA_CHECK(cudaEventRecord(events.gathered));
    UploadAsync(nodeBegins_, plan_.NodeBegins());
    const uint32_t nodeItems = plan_.NodeBegins().back();
    ParallelForCuda(0, nodeItems, RefitLeavesStep{Work(), nodeBegins_.Data()});
    ParallelForCuda(0, nodeItems, RefitUpStep{Work(), nodeBegins_.Data()});
    if (terms_.Size() < nodeItems) terms_.Resize(nodeItems);
    if (costs_.Size() < jobs) costs_.Resize(jobs);
    ParallelForCuda(0, nodeItems, SahTermsStep{Work(), nodeBegins_.Data(), terms_.Data()});
    size_t bytes = 0;
    RT_CUDA_CHECK(cub::DeviceSegmentedReduce::Sum(nullptr, bytes, terms_.Data(), costs_.Data(),
                                                  int(jobs), nodeBegins_.Data(),
                                                  nodeBegins_.Data() + 1));
    if (scratch_.Size() < bytes) scratch_.Resize(bytes);
    RT_CUDA_CHECK(cub::DeviceSegmentedReduce::Sum(scratch_.Data(), bytes, terms_.Data(),
                                                  costs_.Data(), int(jobs), nodeBegins_.Data(),
                                                  nodeBegins_.Data() + 1));
    if (costsCapacity_ < jobs) {
        if (costsHost_) RT_CUDA_CHECK(cudaFreeHost(costsHost_));
        RT_CUDA_CHECK(cudaMallocHost(&costsHost_, jobs * sizeof(float)));
        costsCapacity_ = jobs;
    }
    RT_CUDA_CHECK(
        cudaMemcpyAsync(costsHost_, costs_.Data(), jobs * sizeof(float), cudaMemcpyDeviceToHost));
    RT_CUDA_CHECK(cudaEventRecord(costsCopied_));
    pendingDeformations_.assign(plan_.JobDeformations().begin(), plan_.JobDeformations().end());
    pendingRebuilt_ = plan_.RebuildFlags();
    ParallelForCuda(0, jobs, BlasBoundsStep{Work(), deviceBlasBounds});
    RT_CUDA_CHECK(cudaEventRecord(events.refit));
    return plan_.DeformationCount() != known;
}

}  // namespace rtrt
