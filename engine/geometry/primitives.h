#pragma once
#include "engine/geometry/aabb.h"
#include "engine/geometry/packed_normal.h"

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

// Per-vertex shading normals of one triangle, in the same order as Triangle, each packed in 32
// bits (packed_normal.h): a third of three floats' bytes, for a change of the shading normal
// below 5e-5 radians.
struct TriangleNormals {
    uint32_t n0, n1, n2;

    RT_HD static TriangleNormals Pack(vec3 a, vec3 b, vec3 c) {
        return {PackNormal(a), PackNormal(b), PackNormal(c)};
    }
    // The unnormalised interpolation at barycentrics (b0, b1, b2).
    RT_HD vec3 At(float b0, float b1, float b2) const {
        return b0 * UnpackNormal(n0) + b1 * UnpackNormal(n1) + b2 * UnpackNormal(n2);
    }
};
static_assert(sizeof(TriangleNormals) == 12);

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
