#pragma once
// The per-item steps that bring deforming BLASes up to date, written once for both back ends
// (the CPU deformer runs them over TBB, the CUDA deformer one thread per item, through
// ParallelFor). A frame's work is a list of jobs, one per deformation whose pose changed; each
// step runs over the jobs' items laid end to end (all their vertices, or triangle slots, or node
// positions) and finds its job by binary search, so that a thousand small meshes cost one launch
// per step, not a thousand.
#include "engine/bvh/build/lbvh_steps.h"
#include "engine/bvh/build/sah_term.h"
#include "engine/geometry/primitives.h"
#include "engine/render_rt/deform/deform_vertex.h"

namespace rtrt {

// One deformation updated this frame: where its data sits in the deformer's pools.
struct DeformJob {
    uint32_t mesh;          // DeformMeshView index
    uint32_t blasId;        // its BLAS slot in the scene
    uint32_t vertexOffset;  // its deformed vertices in DeformPools::positions and normals
    uint32_t slotOffset;    // its leaf-ordered triangles
    uint32_t nodeOffset;    // its tree (node positions relative to this; parents likewise)
    uint32_t nodeCount;     // positions its current tree uses
    DeformPose pose;
};

// The deformer's arrays: every deformation's deformed vertices, leaf-ordered triangles and tree.
struct DeformPools {
    vec3* positions;
    uint32_t* normals;  // packed (packed_normal.h) once per vertex, copied to each corner
    Triangle* triangles;
    TriangleNormals* triangleNormals;  // per slot; unused for flat meshes
    TriangleUvs* triangleUvs;          // per slot; unused for untextured meshes
    TriangleColors* triangleColors;    // per slot; unused for meshes without vertex colours
    uint32_t* slotTriangle;            // leaf slot -> triangle of the rest mesh
    BvhNode* nodes;
    uint32_t* parents;  // relative to the job's nodeOffset; the root's is kLbvhNoParent
};

// The job whose items [begins[j], begins[j + 1]) hold item i.
RT_HD inline uint32_t FindJob(const uint32_t* begins, uint32_t jobCount, uint32_t i) {
    uint32_t lo = 0, hi = jobCount;  // begins[lo] <= i < begins[hi]
    while (hi - lo > 1) {
        const uint32_t mid = (lo + hi) / 2;
        if (begins[mid] <= i)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

struct DeformJobs {
    const DeformJob* jobs;
    uint32_t count;
    const DeformMeshView* meshes;
    DeformPools pools;
};

struct DeformVerticesStep {
    DeformJobs work;
    const uint32_t* vertexBegins;
    RT_HD void operator()(size_t i) const {
        const uint32_t j = FindJob(vertexBegins, work.count, uint32_t(i));
        const DeformJob& job = work.jobs[j];
        const uint32_t v = uint32_t(i) - vertexBegins[j];
        vec3 n;
        const vec3 p = DeformVertex(work.meshes[job.mesh], job.pose, v, &n);
        work.pools.positions[job.vertexOffset + v] = p;
        work.pools.normals[job.vertexOffset + v] = PackNormalRounded(n);
    }
};

// Leaf-ordered triangles (and normals; with `reordered`, texture coordinates and colours, which
// only a rebuild's new order changes) from the deformed vertices.
struct GatherTrianglesStep {
    DeformJobs work;
    const uint32_t* slotBegins;
    bool reordered;
    RT_HD void operator()(size_t i) const {
        const uint32_t j = FindJob(slotBegins, work.count, uint32_t(i));
        const DeformJob& job = work.jobs[j];
        const DeformMeshView& mesh = work.meshes[job.mesh];
        const uint32_t slot = job.slotOffset + (uint32_t(i) - slotBegins[j]);
        const glm::uvec3 idx = mesh.indices[work.pools.slotTriangle[slot]];
        const vec3* p = work.pools.positions + job.vertexOffset;
        work.pools.triangles[slot] = {p[idx.x], p[idx.y], p[idx.z]};
        if (mesh.normals) {
            const uint32_t* n = work.pools.normals + job.vertexOffset;
            work.pools.triangleNormals[slot] = {n[idx.x], n[idx.y], n[idx.z]};
        }
        if (reordered && mesh.uvs)
            work.pools.triangleUvs[slot] = {mesh.uvs[idx.x], mesh.uvs[idx.y], mesh.uvs[idx.z]};
        if (reordered && mesh.colors)
            work.pools.triangleColors[slot] =
                TriangleColors::Pack(mesh.colors[idx.x], mesh.colors[idx.y], mesh.colors[idx.z]);
    }
};

// The box of each triangle of one job's rest-mesh order (what a rebuild sorts).
struct TriangleBoxesStep {
    DeformMeshView mesh;
    const vec3* positions;  // the job's deformed vertices
    Aabb* boxes;
    RT_HD void operator()(size_t t) const {
        const glm::uvec3 idx = mesh.indices[t];
        Aabb b;
        b.Grow(positions[idx.x]);
        b.Grow(positions[idx.y]);
        b.Grow(positions[idx.z]);
        boxes[t] = b;
    }
};

// Leaves take the box of their triangles.
struct RefitLeavesStep {
    DeformJobs work;
    const uint32_t* nodeBegins;
    RT_HD void operator()(size_t i) const {
        const uint32_t j = FindJob(nodeBegins, work.count, uint32_t(i));
        const DeformJob& job = work.jobs[j];
        const uint32_t at = job.nodeOffset + (uint32_t(i) - nodeBegins[j]);
        BvhNode& node = work.pools.nodes[at];
        if (!node.IsLeaf()) return;
        const Triangle* tri = work.pools.triangles + job.slotOffset + node.leftFirst;
        Aabb b;
        for (uint32_t k = 0; k < node.primCount; ++k) b.Grow(tri[k].Bounds());
        node.SetBounds(b);
    }
};

// Interior boxes bottom-up: each leaf walks towards the root, the second arrival at a node
// computes it (the LBVH's walk, lbvh_steps.h).
struct RefitUpStep {
    DeformJobs work;
    const uint32_t* nodeBegins;
    RT_HD void operator()(size_t i) const {
        const uint32_t j = FindJob(nodeBegins, work.count, uint32_t(i));
        const DeformJob& job = work.jobs[j];
        const uint32_t p = uint32_t(i) - nodeBegins[j];
        BvhNode* nodes = work.pools.nodes + job.nodeOffset;
        if (p == 0 || p == 1 || !nodes[p].IsLeaf()) return;
        LbvhBoundsBottomUp<LbvhPositionParents>::WalkUp({work.pools.parents + job.nodeOffset},
                                                        nodes, p);
    }
};

// Each position's SAH term (sah_term.h); the deformer sums them per job.
struct SahTermsStep {
    DeformJobs work;
    const uint32_t* nodeBegins;
    float* terms;
    RT_HD void operator()(size_t i) const {
        const uint32_t j = FindJob(nodeBegins, work.count, uint32_t(i));
        const DeformJob& job = work.jobs[j];
        terms[i] = SahNodeTerm(work.pools.nodes + job.nodeOffset, uint32_t(i) - nodeBegins[j]);
    }
};

// The new root box of each job's BLAS, for its instances' world boxes.
struct BlasBoundsStep {
    DeformJobs work;
    Aabb* blasBounds;
    RT_HD void operator()(size_t j) const {
        const DeformJob& job = work.jobs[j];
        blasBounds[job.blasId] = work.pools.nodes[job.nodeOffset].Bounds();
    }
};

}  // namespace rtrt
