#pragma once
// Vertex normals of a triangle mesh that brings none (mesh loaders, procedural shapes, tests).
#include <cmath>
#include <utility>
#include <vector>

#include "engine/geometry/triangle_mesh.h"

namespace rtrt {

// Sets mesh.normals to area-weighted vertex normals: the normalised sum of the cross products of
// the triangles around each vertex. A vertex on no triangle of nonzero area gets +y. The indices
// must be in range.
inline void ComputeSmoothNormals(TriangleMesh& mesh) {
    std::vector<vec3> normals(mesh.positions.size(), vec3(0.0f));
    for (const glm::uvec3& t : mesh.indices) {
        vec3 p0 = mesh.positions[t.x];
        // The cross product's length is twice the triangle's area: the sum is area-weighted.
        vec3 n = glm::cross(mesh.positions[t.y] - p0, mesh.positions[t.z] - p0);
        normals[t.x] += n;
        normals[t.y] += n;
        normals[t.z] += n;
    }
    for (vec3& n : normals) {
        float length = glm::length(n);
        n = length > 0.0f && std::isfinite(length) ? n / length : vec3(0.0f, 1.0f, 0.0f);
    }
    mesh.normals = std::move(normals);
}

}  // namespace rtrt
