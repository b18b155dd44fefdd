#pragma once
// Vertex normals of a triangle mesh that brings none (mesh loaders, procedural shapes, tests).
#include <cmath>
#include <utility>
#include <vector>

#include "engine/core/math.h"
#include "engine/geometry/aabb.h"
#include "engine/geometry/triangle_mesh.h"

namespace rtrt {

// Sets mesh.normals to area-weighted vertex normals: the normalised sum of the cross products of
// the triangles around each vertex. A vertex on no triangle of nonzero area gets +y. The indices
// must be in range.
inline void ComputeSmoothNormals(TriangleMesh& mesh) {
    // Edges are scaled by a power of two (exactly) towards 1 where the mesh's extent is far from
    // it: a cross product of edges of 1e10, or of 1e-15, overflowed or underflowed in float, and
    // every vertex got +y. Meshes of ordinary size keep their bits.
    float extent = 0.0f;
    if (!mesh.positions.empty()) {
        Aabb bounds;
        for (const vec3& p : mesh.positions) bounds.Grow(p);
        extent = MaxComponent(bounds.max - bounds.min);
    }
    float scale = 1.0f;
    if (std::isfinite(extent) && extent > 0.0f && (extent > 0x1p20f || extent < 0x1p-20f))
        scale = std::ldexp(1.0f, -std::ilogb(extent));
    std::vector<vec3> normals(mesh.positions.size(), vec3(0.0f));
    for (const glm::uvec3& t : mesh.indices) {
        vec3 p0 = mesh.positions[t.x];
        // The cross product's length is twice the triangle's area: the sum is area-weighted.
        vec3 n = glm::cross(scale * (mesh.positions[t.y] - p0), scale * (mesh.positions[t.z] - p0));
        normals[t.x] += n;
        normals[t.y] += n;
        normals[t.z] += n;
    }
    for (vec3& n : normals) {
        const bool finite = IsFinite(n);
        if (finite) n = ScaledForNormalize(n);
        float length = glm::length(n);
        n = finite && length > 0.0f && std::isfinite(length) ? n / length : vec3(0.0f, 1.0f, 0.0f);
    }
    mesh.normals = std::move(normals);
}

}  // namespace rtrt
