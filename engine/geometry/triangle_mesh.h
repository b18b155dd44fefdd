#pragma once
// An indexed triangle mesh as loaders produce it; the BLAS builder turns it into leaf-ordered
// triangles.
#include <vector>

#include "engine/geometry/aabb.h"

namespace rtrt {

struct TriangleMesh {
    std::vector<vec3> positions;
    std::vector<vec3> normals;  // per vertex; empty means flat shading
    std::vector<vec2> uvs;      // per vertex; empty means untextured
    std::vector<vec3> colors;   // per vertex, linear RGB in [0, 1]; empty means none
    // Per vertex (see TriangleTangents), for normal maps; empty means tangents from each
    // triangle's uvs at the hit.
    std::vector<vec4> tangents;
    std::vector<glm::uvec3> indices;

    // Of the vertices the triangles use (all of them where there are none): a vertex no triangle
    // names (PLY and OBJ files have them) is no part of the shape, and had moved `fit`.
    Aabb Bounds() const {
        Aabb b;
        if (indices.empty()) {
            for (vec3 p : positions) b.Grow(p);
            return b;
        }
        for (const glm::uvec3& t : indices)
            for (int k = 0; k < 3; ++k)
                if (t[k] < positions.size()) b.Grow(positions[t[k]]);
        return b;
    }
};

}  // namespace rtrt
