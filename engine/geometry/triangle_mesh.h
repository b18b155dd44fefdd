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
    // Per vertex (see TriangleTangents), for normal maps; empty means tangents from each
    // triangle's uvs at the hit.
    std::vector<vec4> tangents;
    std::vector<glm::uvec3> indices;

    Aabb Bounds() const {
        Aabb b;
        for (vec3 p : positions) b.Grow(p);
        return b;
    }
};

}  // namespace rtrt
