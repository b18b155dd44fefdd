#pragma once
// The CPU back end's deforming BLASes: each deformation's vertices, leaf-ordered triangles and
// tree in host pools, brought up to date by the shared steps (deform_steps.h) over TBB, and
// rebuilt with the host LBVH when the policy says so.
#include <span>
#include <vector>

#include "engine/render_rt/deform/deform_plan.h"
#include "engine/render_rt/deform/deform_stats.h"

namespace rtrt {

class CpuDeformer {
  public:
    explicit CpuDeformer(BlasRebuildPolicy policy = {}) : plan_(policy) {}

    // Updates the deformations listed in `changed` and any the scene gained; points their BLAS
    // slots in `views` and `bounds` (indexed by BLAS id, already sized to the scene's BLASes) at
    // the deformed trees.
    DeformStats Update(const RenderScene& scene, std::span<const uint32_t> changed,
                       std::vector<BlasView>& views, std::vector<Aabb>& bounds);

    const DeformPlan& Plan() const { return plan_; }
    // Deformation d's BLAS as it stands (tree, leaf-ordered triangles, slot -> rest triangle as
    // primIds), for tests and benchmarks.
    Blas Snapshot(uint32_t deformation) const;

  private:
    void Admit(const RenderScene& scene);
    DeformJobs Work();
    BlasView ViewOf(uint32_t deformation) const;
    void Rebuild(uint32_t job);

    DeformPlan plan_;
    std::vector<DeformMeshView> meshes_;
    std::vector<vec3> positions_;
    std::vector<uint32_t> normals_;  // packed
    std::vector<Triangle> triangles_;
    std::vector<TriangleNormals> triangleNormals_;
    std::vector<TriangleUvs> triangleUvs_;
    std::vector<TriangleColors> triangleColors_;  // empty until a mesh with colours comes
    std::vector<uint32_t> slotTriangle_;
    AlignedVector<BvhNode> nodes_;
    std::vector<uint32_t> parents_;
    std::vector<float> terms_;
    std::vector<Aabb> boxes_;
};

}  // namespace rtrt
