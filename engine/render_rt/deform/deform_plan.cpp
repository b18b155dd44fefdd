#include "engine/render_rt/deform/deform_plan.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rtrt {

float TreeSahCost(std::span<const BvhNode> nodes) {
    float cost = 0.0f;
    for (uint32_t i = 0; i < nodes.size(); ++i) cost += SahNodeTerm(nodes.data(), i);
    return cost;
}

std::vector<uint32_t> TreeParents(std::span<const BvhNode> nodes) {
    std::vector<uint32_t> parents(nodes.size(), kLbvhNoParent);
    for (uint32_t p = 0; p < nodes.size(); ++p) {
        if (p == 1 || nodes[p].IsLeaf()) continue;
        const uint32_t left = nodes[p].leftFirst;
        if (left + 1 < nodes.size()) parents[left] = parents[left + 1] = p;
    }
    return parents;
}

DeformMeshView HostMeshView(const DeformableMesh& mesh) {
    auto orNull = [](const auto& v) { return v.empty() ? nullptr : v.data(); };
    DeformMeshView view;
    view.positions = mesh.rest.positions.data();
    view.normals = orNull(mesh.rest.normals);
    view.indices = mesh.rest.indices.data();
    view.uvs = orNull(mesh.rest.uvs);
    view.colors = orNull(mesh.rest.colors);
    view.joints = orNull(mesh.joints);
    view.weights = orNull(mesh.weights);
    view.positionDeltas = orNull(mesh.positionDeltas);
    view.normalDeltas = orNull(mesh.normalDeltas);
    view.vertexCount = mesh.VertexCount();
    view.triangleCount = uint32_t(mesh.rest.indices.size());
    view.influences = mesh.influences;
    view.targetCount = mesh.targetCount;
    return view;
}

std::vector<DeformSlotInit> DeformPlan::Admit(const RenderScene& scene) {
    std::vector<DeformSlotInit> added;
    meshCount_ = scene.deformableMeshes.size();
    for (uint32_t d = uint32_t(slots_.size()); d < scene.deformations.size(); ++d) {
        const Deformation& def = scene.deformations[d];
        const std::string at = "deformation " + std::to_string(d);
        if (def.mesh >= scene.deformableMeshes.size() || def.blasId >= scene.blases.size())
            throw std::invalid_argument(at + ": mesh or BLAS out of range");
        const DeformableMesh& mesh = *scene.deformableMeshes[def.mesh];
        const Blas& rest = *scene.blases[def.blasId];
        // A spatial-split BLAS has more leaf slots than triangles: each slot names its triangle.
        if (rest.kind != GeometryKind::kTriangles ||
            rest.SourcePrimCount() != mesh.rest.indices.size())
            throw std::invalid_argument(at + ": its BLAS is not the mesh's triangles");
        if (rest.uvs.empty() != mesh.rest.uvs.empty() ||
            rest.colors.empty() != mesh.rest.colors.empty())
            throw std::invalid_argument(at + ": its BLAS and mesh differ in uvs or colours");
        Entry slot;
        slot.place.mesh = def.mesh;
        slot.place.blasId = def.blasId;
        slot.place.vertexOffset = vertexTotal_;
        slot.place.slotOffset = slotTotal_;
        slot.place.nodeOffset = nodeTotal_;
        slot.place.nodeCount = uint32_t(rest.nodes.size());
        slot.slotCount = rest.PrimCount();
        slot.rebuiltCost = slot.lastCost = TreeSahCost(rest.nodes);
        // Room for the largest tree it may get: an LBVH of one triangle per leaf.
        // Even, so that every tree's node pairs start on a cache line as the layout wants.
        const uint32_t capacity =
            (std::max(uint32_t(rest.nodes.size()), 2 * slot.slotCount) + 1) & ~1u;
        vertexTotal_ += mesh.VertexCount();
        slotTotal_ += slot.slotCount;
        nodeTotal_ += capacity;
        slots_.push_back(slot);
        added.push_back({d, &rest, TreeParents(rest.nodes)});
    }
    planned_.resize(slots_.size(), 0);
    return added;
}

void DeformPlan::PlanFrame(const RenderScene& scene, std::span<const uint32_t> changed) {
    jobs_.clear();
    jobDeformation_.clear();
    rebuildJobs_.clear();
    jointOffset_.clear();
    weightOffset_.clear();
    joints_.clear();
    weights_.clear();
    std::vector<uint32_t> order;
    for (uint32_t d : changed)
        if (d < slots_.size() && !planned_[d]) {
            planned_[d] = 1;
            order.push_back(d);
        }
    for (uint32_t d = 0; d < slots_.size(); ++d)
        if (slots_[d].fresh && !planned_[d]) {
            planned_[d] = 1;
            order.push_back(d);
        }
    std::sort(order.begin(), order.end());
    vertexBegins_.assign(1, 0);
    slotBegins_.assign(1, 0);
    nodeBegins_.assign(1, 0);
    for (uint32_t d : order) {
        planned_[d] = 0;
        Entry& slot = slots_[d];
        slot.fresh = false;
        const Deformation& def = scene.deformations[d];
        const DeformableMesh& mesh = *scene.deformableMeshes[def.mesh];
        if (def.jointMatrices.size() < mesh.jointCount ||
            def.morphWeights.size() < mesh.targetCount)
            throw std::invalid_argument(
                "deformation " + std::to_string(d) +
                ": fewer joint matrices or morph weights than its mesh has");
        const uint32_t job = uint32_t(jobs_.size());
        // A cost that is infinite or not a number (a mesh blown up past float's areas) rebuilds
        // rather than stop every later rebuild (no cost compares above it).
        const bool rebuild = policy_.mode == BlasRebuildPolicy::Mode::kAlwaysRebuild ||
                             (policy_.mode == BlasRebuildPolicy::Mode::kAdaptive &&
                              (!std::isfinite(slot.rebuiltCost) || !std::isfinite(slot.lastCost) ||
                               slot.lastCost > (1.0f + policy_.maxSahGrowth) * slot.rebuiltCost));
        if (rebuild) rebuildJobs_.push_back(job);
        DeformJob j = slot.place;
        j.pose.procedural = def.procedural;
        j.pose.joints = nullptr;
        j.pose.morphWeights = nullptr;
        jointOffset_.push_back(uint32_t(joints_.size()));
        weightOffset_.push_back(uint32_t(weights_.size()));
        joints_.insert(joints_.end(), def.jointMatrices.begin(),
                       def.jointMatrices.begin() + mesh.jointCount);
        weights_.insert(weights_.end(), def.morphWeights.begin(),
                        def.morphWeights.begin() + mesh.targetCount);
        jobs_.push_back(j);
        jobDeformation_.push_back(d);
        vertexBegins_.push_back(vertexBegins_.back() + mesh.VertexCount());
        slotBegins_.push_back(slotBegins_.back() + slot.slotCount);
        nodeBegins_.push_back(nodeBegins_.back() + j.nodeCount);
    }
}

void DeformPlan::SetNodeCount(uint32_t job, uint32_t nodeCount) {
    const uint32_t d = jobDeformation_[job];
    slots_[d].place.nodeCount = nodeCount;
    jobs_[job].nodeCount = nodeCount;
    // Later jobs' node items move; the back end re-plans its node steps from these.
    nodeBegins_.assign(1, 0);
    for (const DeformJob& j : jobs_) nodeBegins_.push_back(nodeBegins_.back() + j.nodeCount);
}

void DeformPlan::ReportCosts(std::span<const uint32_t> deformations,
                             std::span<const uint8_t> rebuilt, std::span<const float> costs) {
    for (size_t j = 0; j < costs.size(); ++j) {
        Entry& slot = slots_[deformations[j]];
        slot.lastCost = costs[j];
        if (rebuilt[j]) slot.rebuiltCost = costs[j];
    }
}

std::vector<uint8_t> DeformPlan::RebuildFlags() const {
    std::vector<uint8_t> flags(jobs_.size(), 0);
    for (uint32_t j : rebuildJobs_) flags[j] = 1;
    return flags;
}

}  // namespace rtrt
