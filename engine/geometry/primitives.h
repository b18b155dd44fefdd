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

// Per-vertex colours of one triangle, in the same order as Triangle (glTF's COLOR_0: linear RGB
// that multiplies the base colour), each channel a 16-bit unsigned normalised value: exact for the
// 8- and 16-bit colours files hold, within 1/131070 of float ones, in half the bytes of floats.
// Alpha is not kept: surfaces are opaque.
struct TriangleColors {
    uint16_t rgb[9];

    // Each channel clamped to [0, 1] and rounded to the nearest step.
    RT_HD static TriangleColors Pack(vec3 a, vec3 b, vec3 c) {
        TriangleColors t;
        const vec3 corners[3] = {a, b, c};
        for (int v = 0; v < 3; ++v)
            for (int k = 0; k < 3; ++k) {
                const float x = corners[v][k];
                const float clamped = x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;  // NaN -> 0
                t.rgb[3 * v + k] = uint16_t(clamped * 65535.0f + 0.5f);
            }
        return t;
    }
    RT_HD vec3 Corner(int v) const {
        constexpr float kScale = 1.0f / 65535.0f;
        return vec3(float(rgb[3 * v]), float(rgb[3 * v + 1]), float(rgb[3 * v + 2])) * kScale;
    }
    // The interpolation at barycentrics (b1, b2) of vertices 1 and 2.
    RT_HD vec3 At(float b1, float b2) const {
        return (1.0f - b1 - b2) * Corner(0) + b1 * Corner(1) + b2 * Corner(2);
    }
};
static_assert(sizeof(TriangleColors) == 18);

enum class GeometryKind : uint32_t { kTriangles = 0, kSpheres = 1 };

}  // namespace rtrt
