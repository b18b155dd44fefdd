#pragma once
// Bottom-level acceleration structure: one BVH over one model's triangles or spheres, with the
// primitives stored in leaf order. Built once per model (offline or at load), shared by every
// instance of the model.
#include <span>
#include <vector>

#include "engine/bvh/build/bvh_builder.h"
#include "engine/bvh/layout/bvh4.h"
#include "engine/geometry/deformable_mesh.h"
#include "engine/geometry/primitives.h"
#include "engine/geometry/triangle_mesh.h"

namespace rtrt {

// What the tracer needs of a BLAS: plain pointers, valid in host or device memory.
struct BlasView {
    const BvhNode* nodes;
    const Bvh4Node* nodes4;          // CPU only: the 4-wide collapse of nodes, or null
    const Triangle* triangles;       // kTriangles: leaf order
    const TriangleNormals* normals;  // kTriangles: leaf order, or null for flat shading
    const Sphere* spheres;           // kSpheres: leaf order
    GeometryKind kind;
    uint32_t primCount;
    const TriangleUvs* uvs;  // kTriangles: leaf order, or null without texture coordinates
    const TriangleTangents* tangents;  // kTriangles: leaf order, or null (per-face tangents)
    const TriangleColors* colors;      // kTriangles: leaf order, or null without vertex colours
};

struct Blas {
    GeometryKind kind = GeometryKind::kTriangles;
    AlignedVector<BvhNode> nodes;
    AlignedVector<Bvh4Node> nodes4;  // CollapseToBvh4(nodes); redo after a refit
    AlignedVector<Triangle> triangles;
    std::vector<TriangleNormals> normals;
    std::vector<Sphere> spheres;
    std::vector<uint32_t> primIds;           // leaf slot -> index in the source mesh or sphere list
    std::vector<TriangleUvs> uvs;            // kTriangles: leaf order, or none
    std::vector<TriangleTangents> tangents;  // kTriangles: leaf order, or none
    std::vector<TriangleColors> colors;      // kTriangles: leaf order, or none
    Aabb bounds;

    uint32_t PrimCount() const { return uint32_t(primIds.size()); }  // leaf slots
    // Distinct source primitives: fewer than the slots when spatial splits put some in several
    // leaves.
    uint32_t SourcePrimCount() const;
    BlasView View() const;
    size_t Bytes() const;        // what the CPU tracer keeps of it (both node layouts too)
    size_t DeviceBytes() const;  // what the GPU holds: binary nodes, primitives, normals, uvs,
                                 // tangents, colours
};

Blas BuildTriangleBlas(const TriangleMesh& mesh, const BvhBuildOptions& options = {});
Blas BuildSphereBlas(std::span<const Sphere> spheres, const BvhBuildOptions& options = {});

// A triangle BLAS's mesh as a deformable rest mesh whose triangle primIds[s] is the BLAS's slot s
// (the first such slot where spatial splits put a triangle in several; three vertices of its own
// per slot, with its normals, uvs and colours), so that the BLAS is the rest tree of the mesh:
// models loaded as BLASes only (.rtmodel caches) can deform too.
DeformableMesh RestMeshOfBlas(const Blas& blas);

// Moves and scales a triangle BLAS in place, p -> (p - centre) * scale with scale > 0, on every
// vertex and node box. Rounding is monotonic, so each box stays exactly the bounds of what it
// holds: the result equals refitting the transformed triangles. Normals need no change.
void ScaleAndMoveBlas(Blas& blas, vec3 centre, float scale);

}  // namespace rtrt
