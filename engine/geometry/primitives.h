#pragma once
#include "engine/geometry/aabb.h"

namespace rtrt {

// Triangle vertices in BVH leaf order, 36 bytes: the tracer reads them contiguously.
struct Triangle {
    vec3 v0, v1, v2;

    RT_HD Aabb Bounds() const {
        Aabb b;
        b.Grow(v0);
        b.Grow(v1);
        b.Grow(v2);
        return b;
    }
};
static_assert(sizeof(Triangle) == 36);

struct Sphere {
    vec3 center;
    float radius;

    RT_HD Aabb Bounds() const { return {center - vec3(radius), center + vec3(radius)}; }
};
static_assert(sizeof(Sphere) == 16);

// Per-vertex shading normals of one triangle, in the same order as Triangle.
struct TriangleNormals {
    vec3 n0, n1, n2;
};
static_assert(sizeof(TriangleNormals) == 36);

// Texture coordinates of one triangle's vertices, in the same order as Triangle (glTF's
// TEXCOORD_0: u right, v down the image).
struct TriangleUvs {
    vec2 uv0, uv1, uv2;
};
static_assert(sizeof(TriangleUvs) == 24);

// Per-vertex tangents of one triangle, in the same order as Triangle, as glTF's TANGENT: xyz the
// tangent (direction of increasing u), w the bitangent's sign (bitangent = cross(normal, xyz) * w).
struct TriangleTangents {
    vec4 t0, t1, t2;
};
static_assert(sizeof(TriangleTangents) == 48);

enum class GeometryKind : uint32_t { kTriangles = 0, kSpheres = 1 };

}  // namespace rtrt
