#pragma once
// Turns a SceneHit into a world-space surface point with a bound on its rounding error, so that
// secondary rays can leave it without a fixed epsilon (pbrt-v4 section 6.8).
#include "engine/render_rt/render_scene_view.h"

namespace rtrt {

struct Surface {
    vec3 point;
    vec3 pointError;     // absolute error bound per component
    vec3 geomNormal;     // unit, faces the incoming ray
    vec3 shadingNormal;  // unit, on the same side as geomNormal
    bool frontFace;      // the ray arrived from outside (against the outward normal)
    uint32_t materialId;
};

RT_HD inline Surface MakeSurface(const RenderSceneView& scene, const Ray& ray,
                                 const SceneHit& hit) {
    const Instance& inst = scene.tlas.instances[hit.instance];
    const BlasView& blas = scene.tlas.blases[inst.blasId];
    vec3 p, pError, ng, ns;
    if (blas.kind == GeometryKind::kTriangles) {
        const Triangle& tri = blas.triangles[hit.prim];
        const float b0 = 1.0f - hit.b1 - hit.b2;
        p = b0 * tri.v0 + hit.b1 * tri.v1 + hit.b2 * tri.v2;
        pError = Gamma(7) * (Abs(b0 * tri.v0) + Abs(hit.b1 * tri.v1) + Abs(hit.b2 * tri.v2));
        ng = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
        ns = ng;
        if (blas.normals) {
            const TriangleNormals& n = blas.normals[hit.prim];
            ns = b0 * n.n0 + hit.b1 * n.n1 + hit.b2 * n.n2;
        }
    } else {
        const Sphere& s = blas.spheres[hit.prim];
        const Ray objectRay = ToObjectSpace(ray, inst);
        p = objectRay.origin + hit.t * objectRay.dir;
        // Reproject onto the sphere: the error then depends on |p| only (pbrt-v4, Sphere).
        vec3 fromCentre = p - s.center;
        p = s.center + fromCentre * (s.radius / glm::length(fromCentre));
        pError = Gamma(5) * Abs(p);
        ng = p - s.center;
        ns = ng;
    }
    Surface surface;
    surface.pointError = inst.objectToWorld.PointError(p, pError);
    surface.point = inst.objectToWorld.Point(p);
    surface.geomNormal = glm::normalize(inst.worldToObject.NormalFromInverse(ng));
    surface.shadingNormal = glm::normalize(inst.worldToObject.NormalFromInverse(ns));
    surface.frontFace = glm::dot(surface.geomNormal, ray.dir) < 0.0f;
    if (!surface.frontFace) surface.geomNormal = -surface.geomNormal;
    if (glm::dot(surface.shadingNormal, surface.geomNormal) < 0.0f)
        surface.shadingNormal = -surface.shadingNormal;
    surface.materialId = inst.materialId;
    return surface;
}

RT_HD inline Ray SpawnRay(const Surface& s, vec3 dir, float tMax = kInfinity) {
    Ray r;
    r.origin = OffsetRayOrigin(s.point, s.pointError, s.geomNormal, dir);
    r.dir = dir;
    r.tMax = tMax;
    r.pad = 0.0f;
    return r;
}

}  // namespace rtrt
