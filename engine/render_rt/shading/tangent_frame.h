#pragma once
// Tangent-space normal maps on triangles. Where the BLAS stores vertex tangents (a glTF file's
// TANGENT, or GenerateTangents' MikkTSpace-like ones), the tangent is interpolated at the hit;
// elsewhere (deforming meshes) it comes from the triangle's positions and texture coordinates at
// the hit (the direction of increasing u, per face). Either is made perpendicular to the
// interpolated shading normal; the bitangent is n x t, its sign the tangent's w (or flipped where
// the uvs are mirrored). glTF's normal textures point +y towards decreasing v (the image's up).
#include "engine/core/affine.h"
#include "engine/geometry/primitives.h"

namespace rtrt {

// The world-space shading normal for tangent-space normal m (components in [-1, 1], x and y
// already times normalScale) on triangle tri (object space) with uvs, in an instance placed by
// objectToWorld, around unit world shading normal n. Returns n where the uvs are degenerate.
RT_HD inline vec3 NormalFromMap(const Triangle& tri, const TriangleUvs& uvs,
                                const Affine& objectToWorld, vec3 n, vec3 m) {
    const vec3 e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
    const vec2 d1 = uvs.uv1 - uvs.uv0, d2 = uvs.uv2 - uvs.uv0;
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (!(fabsf(det) > 0.0f)) return n;
    const vec3 dpdu = objectToWorld.Vector((e1 * d2.y - e2 * d1.y) / det);
    const vec3 dpdv = objectToWorld.Vector((e2 * d1.x - e1 * d2.x) / det);
    vec3 t = dpdu - n * glm::dot(n, dpdu);
    const float tLength = glm::length(t);
    if (!(tLength > 0.0f)) return n;
    t /= tLength;
    vec3 b = glm::cross(n, t);
    if (glm::dot(b, dpdv) > 0.0f) b = -b;  // +y of the map runs towards decreasing v
    const vec3 mapped = m.x * t + m.y * b + m.z * n;
    const float length = glm::length(mapped);
    return length > 0.0f ? mapped / length : n;
}

// The same with the triangle's vertex tangents, interpolated at barycentrics (b1, b2). An
// instance that mirrors (negative determinant) mirrors the bitangent too.
RT_HD inline vec3 NormalFromTangents(const TriangleTangents& tangents, float b1, float b2,
                                     const Affine& objectToWorld, vec3 n, vec3 m) {
    const vec4 objectTangent = (1.0f - b1 - b2) * tangents.t0 + b1 * tangents.t1 + b2 * tangents.t2;
    vec3 t = objectToWorld.Vector(vec3(objectTangent));
    t -= n * glm::dot(n, t);
    const float tLength = glm::length(t);
    if (!(tLength > 0.0f)) return n;
    t /= tLength;
    const float det = glm::dot(vec3(objectToWorld.row[0]),
                               glm::cross(vec3(objectToWorld.row[1]), vec3(objectToWorld.row[2])));
    const float sign = (tangents.t0.w < 0.0f) != (det < 0.0f) ? -1.0f : 1.0f;
    const vec3 b = sign * glm::cross(n, t);
    const vec3 mapped = m.x * t + m.y * b + m.z * n;
    const float length = glm::length(mapped);
    return length > 0.0f ? mapped / length : n;
}

}  // namespace rtrt
