#include "engine/render_rt/cpu/cpu_deformer.h"

#include <algorithm>
#include <numeric>

#include "engine/bvh/build/lbvh.h"
#include "engine/core/parallel_for.h"
#include "engine/core/timer.h"

namespace rtrt {

void CpuDeformer::Admit(const RenderScene& scene) {
    const std::vector<DeformSlotInit> added = plan_.Admit(scene);
    for (size_t m = meshes_.size(); m < plan_.MeshCount(); ++m)
        meshes_.push_back(HostMeshView(*scene.deformableMeshes[m]));
    if (added.empty()) return;
    positions_.resize(plan_.VertexTotal());
    normals_.resize(plan_.VertexTotal());
    triangles_.resize(plan_.SlotTotal());
    triangleNormals_.resize(plan_.SlotTotal());
    triangleUvs_.resize(plan_.SlotTotal());
    if (!triangleColors_.empty() || AnyColors(added)) triangleColors_.resize(plan_.SlotTotal());
    slotTriangle_.resize(plan_.SlotTotal());
    nodes_.resize(plan_.NodeTotal());
    parents_.resize(plan_.NodeTotal(), kLbvhNoParent);
    for (const DeformSlotInit& init : added) {
        const DeformJob& at = plan_.Slot(init.deformation);
        std::copy(init.rest->nodes.begin(), init.rest->nodes.end(), nodes_.begin() + at.nodeOffset);
        std::copy(init.parents.begin(), init.parents.end(), parents_.begin() + at.nodeOffset);
        std::copy(init.rest->primIds.begin(), init.rest->primIds.end(),
                  slotTriangle_.begin() + at.slotOffset);
        std::copy(init.rest->uvs.begin(), init.rest->uvs.end(),
                  triangleUvs_.begin() + at.slotOffset);
        if (!init.rest->colors.empty())
            std::copy(init.rest->colors.begin(), init.rest->colors.end(),
                      triangleColors_.begin() + at.slotOffset);
    }
}

DeformJobs CpuDeformer::Work() {
    DeformPools pools{positions_.data(),       normals_.data(),     triangles_.data(),
                      triangleNormals_.data(), triangleUvs_.data(), triangleColors_.data(),
                      slotTriangle_.data(),    nodes_.data(),       parents_.data()};
    return {plan_.Jobs().data(), uint32_t(plan_.Jobs().size()), meshes_.data(), pools};
}

BlasView CpuDeformer::ViewOf(uint32_t d) const {
    const DeformJob& at = plan_.Slot(d);
    const DeformMeshView& mesh = meshes_[at.mesh];
    BlasView v{};
    v.nodes = nodes_.data() + at.nodeOffset;
    v.nodes4 = nullptr;  // refit trees are traversed in their binary layout
    v.triangles = triangles_.data() + at.slotOffset;
    v.normals = mesh.normals ? triangleNormals_.data() + at.slotOffset : nullptr;
    v.spheres = nullptr;
    v.kind = GeometryKind::kTriangles;
    v.primCount = plan_.SlotCount(d);
    v.uvs = mesh.uvs ? triangleUvs_.data() + at.slotOffset : nullptr;
    v.colors = mesh.colors ? triangleColors_.data() + at.slotOffset : nullptr;
    return v;
}

Blas CpuDeformer::Snapshot(uint32_t d) const {
    const DeformJob& at = plan_.Slot(d);
    const uint32_t n = plan_.SlotCount(d);
    const BlasView v = ViewOf(d);
    Blas blas;
    blas.nodes.assign(nodes_.begin() + at.nodeOffset,
                      nodes_.begin() + at.nodeOffset + at.nodeCount);
    blas.triangles.assign(v.triangles, v.triangles + n);
    if (v.normals) blas.normals.assign(v.normals, v.normals + n);
    if (v.uvs) blas.uvs.assign(v.uvs, v.uvs + n);
    if (v.colors) blas.colors.assign(v.colors, v.colors + n);
    blas.primIds.assign(slotTriangle_.begin() + at.slotOffset,
                        slotTriangle_.begin() + at.slotOffset + n);
    blas.bounds = blas.nodes[0].Bounds();
    return blas;
}

// An LBVH over the deformed triangles replaces the job's tree.
void CpuDeformer::Rebuild(uint32_t j) {
    const DeformJob& job = plan_.Jobs()[j];
    const DeformMeshView& mesh = meshes_[job.mesh];
    boxes_.resize(mesh.triangleCount);
    ParallelFor(0, mesh.triangleCount, 4096,
                TriangleBoxesStep{mesh, positions_.data() + job.vertexOffset, boxes_.data()});
    const Lbvh tree = BuildLbvh(boxes_);
    std::copy(tree.nodes.begin(), tree.nodes.end(), nodes_.begin() + job.nodeOffset);
    std::copy(tree.parents.begin(), tree.parents.end(), parents_.begin() + job.nodeOffset);
    std::copy(tree.primOrder.begin(), tree.primOrder.end(), slotTriangle_.begin() + job.slotOffset);
    plan_.SetNodeCount(j, uint32_t(tree.nodes.size()));
}

DeformStats CpuDeformer::Update(const RenderScene& scene, std::span<const uint32_t> changed,
                                std::vector<BlasView>& views, std::vector<Aabb>& bounds) {
    DeformStats stats;
    const uint32_t known = plan_.DeformationCount();
    Admit(scene);
    plan_.PlanFrame(scene, changed);
    const uint32_t jobs = uint32_t(plan_.Jobs().size());
    if (jobs == 0) return stats;
    Stopwatch timer;
    for (uint32_t j = 0; j < jobs; ++j) {
        stats.triangles += plan_.SlotCount(plan_.JobDeformations()[j]);
        DeformJob& job = plan_.MutableJobs()[j];
        job.pose.joints = plan_.JointMatrices().data() + plan_.JointOffset(j);
        job.pose.morphWeights = plan_.MorphWeights().data() + plan_.WeightOffset(j);
    }
    ParallelFor(0, plan_.VertexBegins().back(), 1024,
                DeformVerticesStep{Work(), plan_.VertexBegins().data()});
    stats.deformMs = timer.Milliseconds();
    timer.Restart();
    for (uint32_t j : plan_.RebuildJobs()) Rebuild(j);
    stats.blasMs = timer.Milliseconds();
    timer.Restart();
    ParallelFor(
        0, plan_.SlotBegins().back(), 1024,
        GatherTrianglesStep{Work(), plan_.SlotBegins().data(), !plan_.RebuildJobs().empty()});
    stats.deformMs += timer.Milliseconds();
    timer.Restart();
    const DeformJobs work = Work();
    const uint32_t* nodeBegins = plan_.NodeBegins().data();
    ParallelFor(0, plan_.NodeBegins().back(), 1024, RefitLeavesStep{work, nodeBegins});
    ParallelFor(0, plan_.NodeBegins().back(), 1024, RefitUpStep{work, nodeBegins});
    terms_.resize(plan_.NodeBegins().back());
    ParallelFor(0, terms_.size(), 4096, SahTermsStep{work, nodeBegins, terms_.data()});
    std::vector<float> costs(jobs, 0.0f);
    // Summed in order per job, as the device's segmented reduction does not promise to: the
    // policy compares a back end's costs only with its own.
    ParallelFor(0, jobs, 1, [&](size_t j) {
        costs[j] = std::accumulate(terms_.begin() + nodeBegins[j],
                                   terms_.begin() + nodeBegins[j + 1], 0.0f);
    });
    const std::vector<uint8_t> rebuilt = plan_.RebuildFlags();
    plan_.ReportCosts(plan_.JobDeformations(), rebuilt, costs);
    BlasBoundsStep roots{work, bounds.data()};
    for (uint32_t j = 0; j < jobs; ++j) roots(j);
    stats.blasMs += timer.Milliseconds();
    stats.deformed = jobs;
    stats.rebuilt = uint32_t(plan_.RebuildJobs().size());
    // New deformations may have moved the pools: every deformed view is pointed again.
    for (uint32_t d = (plan_.DeformationCount() != known ? 0 : known); d < plan_.DeformationCount();
         ++d)
        views[plan_.Slot(d).blasId] = ViewOf(d);
    return stats;
}

}  // namespace rtrt
