#pragma once
// Closed triangle meshes with shared vertices (every edge belongs to exactly two triangles), and
// a point known to lie inside each: the targets of the watertightness cases.
#include <set>
#include <utility>
#include <vector>

#include "engine/geometry/triangle_mesh.h"

namespace rtrt::robust {

struct ClosedMesh {
    const char* name;
    TriangleMesh mesh;
    vec3 inside;  // a point strictly inside the solid
    bool convex;  // then the segment from `inside` to any surface point meets the surface once
};

// A UV sphere: the poles are vertices shared by a whole fan of `slices` triangles.
inline ClosedMesh UvSphere(uint32_t slices, uint32_t stacks, float radius, vec3 centre) {
    ClosedMesh m{"uv_sphere", {}, centre, true};
    m.mesh.positions.push_back(centre + vec3(0, radius, 0));
    for (uint32_t j = 1; j < stacks; ++j) {
        const float theta = kPi * float(j) / float(stacks);
        for (uint32_t i = 0; i < slices; ++i) {
            const float phi = 2.0f * kPi * float(i) / float(slices);
            m.mesh.positions.push_back(centre + radius * vec3(std::sin(theta) * std::cos(phi),
                                                              std::cos(theta),
                                                              std::sin(theta) * std::sin(phi)));
        }
    }
    m.mesh.positions.push_back(centre - vec3(0, radius, 0));
    const uint32_t south = uint32_t(m.mesh.positions.size() - 1);
    auto ring = [&](uint32_t j, uint32_t i) { return 1 + (j - 1) * slices + i % slices; };
    for (uint32_t i = 0; i < slices; ++i) {
        m.mesh.indices.push_back({0, ring(1, i + 1), ring(1, i)});
        m.mesh.indices.push_back({south, ring(stacks - 1, i), ring(stacks - 1, i + 1)});
        for (uint32_t j = 1; j + 1 < stacks; ++j) {
            m.mesh.indices.push_back({ring(j, i), ring(j, i + 1), ring(j + 1, i + 1)});
            m.mesh.indices.push_back({ring(j, i), ring(j + 1, i + 1), ring(j + 1, i)});
        }
    }
    return m;
}

// A box whose faces are n x n grids of quads, corners at lo and hi: long diagonals, T-free
// seams along the box edges, coordinates that are not exact in binary when lo/hi are not.
inline ClosedMesh SubdividedBox(uint32_t n, vec3 lo, vec3 hi) {
    ClosedMesh m{"subdivided_box", {}, 0.5f * (lo + hi), true};
    // One vertex per lattice point on the surface, shared by the faces that meet there.
    auto index = [&](uint32_t i, uint32_t j, uint32_t k) {
        return (i * (n + 1) + j) * (n + 1) + k;
    };
    for (uint32_t i = 0; i <= n; ++i)
        for (uint32_t j = 0; j <= n; ++j)
            for (uint32_t k = 0; k <= n; ++k)
                m.mesh.positions.push_back(lo + (hi - lo) * vec3(i, j, k) / float(n));
    // Each face: axis a fixed at 0 or n; (u, v) span the other two, wound to face outward.
    for (int axis = 0; axis < 3; ++axis)
        for (uint32_t side = 0; side <= n; side += n)
            for (uint32_t u = 0; u < n; ++u)
                for (uint32_t v = 0; v < n; ++v) {
                    auto at = [&](uint32_t du, uint32_t dv) {
                        uint32_t c[3];
                        c[axis] = side;
                        c[(axis + 1) % 3] = u + du;
                        c[(axis + 2) % 3] = v + dv;
                        return index(c[0], c[1], c[2]);
                    };
                    glm::uvec3 t0{at(0, 0), at(1, 0), at(1, 1)}, t1{at(0, 0), at(1, 1), at(0, 1)};
                    if (side == 0) std::swap(t0.y, t0.z), std::swap(t1.y, t1.z);
                    m.mesh.indices.push_back(t0);
                    m.mesh.indices.push_back(t1);
                }
    return m;
}

// A torus around +y: not convex, every vertex shared by six triangles.
inline ClosedMesh Torus(uint32_t ringSegments, uint32_t tubeSegments, float major, float minor) {
    ClosedMesh m{"torus", {}, vec3(major, 0, 0), false};
    for (uint32_t i = 0; i < ringSegments; ++i) {
        const float phi = 2.0f * kPi * float(i) / float(ringSegments);
        for (uint32_t j = 0; j < tubeSegments; ++j) {
            const float theta = 2.0f * kPi * float(j) / float(tubeSegments);
            const float r = major + minor * std::cos(theta);
            m.mesh.positions.push_back(
                vec3(r * std::cos(phi), minor * std::sin(theta), r * std::sin(phi)));
        }
    }
    auto at = [&](uint32_t i, uint32_t j) {
        return (i % ringSegments) * tubeSegments + j % tubeSegments;
    };
    for (uint32_t i = 0; i < ringSegments; ++i)
        for (uint32_t j = 0; j < tubeSegments; ++j) {
            m.mesh.indices.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
            m.mesh.indices.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
    return m;
}

// Each undirected edge once, as a pair of vertex indices.
inline std::vector<std::pair<uint32_t, uint32_t>> UniqueEdges(const TriangleMesh& mesh) {
    std::set<std::pair<uint32_t, uint32_t>> edges;
    for (const glm::uvec3& t : mesh.indices)
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = t[e], b = t[(e + 1) % 3];
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    return {edges.begin(), edges.end()};
}

}  // namespace rtrt::robust
