#pragma once
// Moller, Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection", JGT 2(1): the
// textbook test, kept as the accuracy benchmark's foil to the watertight test. Each triangle
// computes its barycentrics from its own edges, so two triangles sharing an edge round the
// edge differently and a ray through it can miss both (tests/accuracy). Hits need only t > 0:
// avoiding self-intersection is left to the ray offset, as in the paper.
#include "engine/geometry/primitives.h"
#include "engine/geometry/ray_setup.h"
#include "engine/geometry/triangle_intersect.h"

namespace rtrt {

RT_HD inline bool IntersectTriangleMollerTrumbore(const Triangle& tri, const RaySetup& r,
                                                  float tMax, TriangleHit* hit) {
    const vec3 e1 = tri.v1 - tri.v0;
    const vec3 e2 = tri.v2 - tri.v0;
    const vec3 p = glm::cross(r.dir, e2);
    const float det = glm::dot(e1, p);
    // The paper culls |det| < 1e-6; an absolute threshold would also cull the dragon's small
    // triangles, so only the exactly parallel case is rejected.
    if (det == 0.0f) return false;
    const float invDet = 1.0f / det;
    const vec3 s = r.origin - tri.v0;
    const float u = glm::dot(s, p) * invDet;
    if (u < 0.0f || u > 1.0f) return false;
    const vec3 q = glm::cross(s, e1);
    const float v = glm::dot(r.dir, q) * invDet;
    if (v < 0.0f || u + v > 1.0f) return false;
    const float t = glm::dot(e2, q) * invDet;
    if (!(t > 0.0f) || t > tMax) return false;
    hit->t = t;
    hit->b1 = u;
    hit->b2 = v;
    return true;
}

}  // namespace rtrt
