#pragma once
// The host's bookkeeping of the deforming BLASes, shared by the CPU and CUDA deformers: where each
// deformation's vertices, triangles and tree sit in the pools, which deformations a frame
// updates (only those whose pose changed, and new ones), each one's pose flattened for upload,
// and the rebuild policy's decisions from the SAH costs the back end reports.
#include <span>
#include <vector>

#include "engine/render_rt/deform/deform_steps.h"
#include "engine/render_rt/render_scene.h"

namespace rtrt {

// The start of a deformation's life in the pools: its rest tree, as the scene's BLAS has it.
struct DeformSlotInit {
    uint32_t deformation;
    const Blas* rest;
    std::vector<uint32_t> parents;  // of rest->nodes
};

// Whether any of the deformations ADDED has vertex colours: the deformers keep a pool of slot
// colours only once one has.
inline bool AnyColors(const std::vector<DeformSlotInit>& added) {
    for (const DeformSlotInit& init : added)
        if (!init.rest->colors.empty()) return true;
    return false;
}

class DeformPlan {
  public:
    explicit DeformPlan(BlasRebuildPolicy policy) : policy_(policy) {}

    // Takes the meshes and deformations the scene has that the plan does not know yet, placing
    // them after the known ones in the pools. Returns what the back end must copy in (empty
    // when nothing is new). Meshes must not change once taken.
    std::vector<DeformSlotInit> Admit(const RenderScene& scene);

    // The jobs of one frame: the changed deformations (and those admitted since the last plan),
    // in increasing deformation order, each with a rebuild or refit decision.
    void PlanFrame(const RenderScene& scene, std::span<const uint32_t> changed);
    // The SAH costs of a planned frame's trees (the GPU's arrive a frame late): for each of its
    // jobs, the deformation, whether it was rebuilt, and the cost.
    void ReportCosts(std::span<const uint32_t> deformations, std::span<const uint8_t> rebuilt,
                     std::span<const float> costs);
    // Per job of the last planned frame: 1 if it is rebuilt.
    std::vector<uint8_t> RebuildFlags() const;
    // A rebuild changed job j's tree to `nodeCount` positions.
    void SetNodeCount(uint32_t job, uint32_t nodeCount);

    std::span<const DeformJob> Jobs() const { return jobs_; }
    std::vector<DeformJob>& MutableJobs() { return jobs_; }
    std::span<const uint32_t> JobDeformations() const { return jobDeformation_; }
    // begins[j]: the first item of job j in the frame's items laid end to end; begins[count]:
    // the total.
    std::span<const uint32_t> VertexBegins() const { return vertexBegins_; }
    std::span<const uint32_t> SlotBegins() const { return slotBegins_; }
    std::span<const uint32_t> NodeBegins() const { return nodeBegins_; }
    std::span<const uint32_t> RebuildJobs() const { return rebuildJobs_; }
    // The frame's poses, flattened: job j's joints start at JointOffset(j), its weights at
    // WeightOffset(j). The back end points each job's pose at its copy of these.
    std::span<const Affine> JointMatrices() const { return joints_; }
    std::span<const float> MorphWeights() const { return weights_; }
    uint32_t JointOffset(uint32_t job) const { return jointOffset_[job]; }
    uint32_t WeightOffset(uint32_t job) const { return weightOffset_[job]; }

    // Pool sizes over every admitted deformation.
    uint32_t VertexTotal() const { return vertexTotal_; }
    uint32_t SlotTotal() const { return slotTotal_; }
    uint32_t NodeTotal() const { return nodeTotal_; }
    uint32_t MeshCount() const { return uint32_t(meshCount_); }
    uint32_t DeformationCount() const { return uint32_t(slots_.size()); }
    // Where deformation d sits (its BLAS view is built from these).
    const DeformJob& Slot(uint32_t d) const { return slots_[d].place; }
    uint32_t SlotCount(uint32_t d) const { return slots_[d].slotCount; }
    float RebuiltCost(uint32_t d) const { return slots_[d].rebuiltCost; }
    float LastCost(uint32_t d) const { return slots_[d].lastCost; }
    const BlasRebuildPolicy& Policy() const { return policy_; }

  private:
    struct Entry {
        DeformJob place;  // offsets, mesh, blasId, current node count
        uint32_t slotCount = 0;
        float rebuiltCost = 0.0f;  // after the tree's last build
        float lastCost = 0.0f;     // after its last refit
        bool fresh = true;         // admitted and not yet planned
    };

    BlasRebuildPolicy policy_;
    std::vector<Entry> slots_;
    size_t meshCount_ = 0;
    uint32_t vertexTotal_ = 0, slotTotal_ = 0, nodeTotal_ = 0;
    std::vector<DeformJob> jobs_;
    std::vector<uint32_t> jobDeformation_, vertexBegins_, slotBegins_, nodeBegins_;
    std::vector<uint32_t> rebuildJobs_, jointOffset_, weightOffset_;
    std::vector<Affine> joints_;
    std::vector<float> weights_;
    std::vector<uint8_t> planned_;  // per deformation: already a job this frame
};

// The SAH cost of a tree of the pair layout (every position's SahNodeTerm, summed in order).
float TreeSahCost(std::span<const BvhNode> nodes);
// Parent positions of a tree of the pair layout (the root's is kLbvhNoParent).
std::vector<uint32_t> TreeParents(std::span<const BvhNode> nodes);
// The view of a mesh's arrays in host memory.
DeformMeshView HostMeshView(const DeformableMesh& mesh);

}  // namespace rtrt
