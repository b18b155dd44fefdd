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

// A sphere's hit point and its error bound, in double from the world ray: the point o + t d along
// the world ray at the trace's t; the bound is how far that point is from the sphere (measured in
// double in the exact object space) and what the object-space direction's rounding to float
// moves it at that t (the root is of the rounded ray, the point on the world ray), both scaled to
// world units by the instance's largest stretch, plus the rounding to float. The float form
// (pbrt-v4's reprojection, error gamma(5) |p| in object space) put points on a ground sphere of
// radius 1e6 0.3 off its surface, and shadow rays started 0.66 above it. Sets point, pointError
// and an object-space geomNormal.
RT_HD inline void SphereSurfacePoint(const Sphere& sphere, const Ray& ray, const Instance& inst,
                                     float tHit, Surface* surface) {
    using glm::dvec3;
    const SphereRay r = ToObjectSpaceExact(ray, inst);
    // The trace's own t: how far its point is from the sphere is measured below, so its rounding
    // is in the bound without solving again.
    const double t = tHit;
    const dvec3 fromCentre = r.origin + t * dvec3(r.dir) - dvec3(sphere.center);
    const double distance = glm::length(fromCentre);
    const double offSphere = fabs(distance - double(sphere.radius)) +
                             GammaDouble(16) * (distance + double(sphere.radius));
    // Frobenius norms of the linear parts: at least their largest stretches.
    float stretch = 0.0f, inverseStretch = 0.0f;
    const Affine objectToWorld = inst.ObjectToWorld();
    for (int i = 0; i < 3; ++i) {
        const vec3 l(objectToWorld.row[i]), w(inst.InverseRow(i));
        stretch += glm::dot(l, l);
        inverseStretch += glm::dot(w, w);
    }
    stretch = (1.0f + Gamma(3)) * sqrtf(stretch);
    inverseStretch = (1.0f + Gamma(3)) * sqrtf(inverseStretch);
    const float worldDirLength = glm::length(ray.dir);
    const double roundedDir = double(Gamma(3)) * fabs(t) * inverseStretch * worldDirLength;
    const dvec3 worldPoint = dvec3(ray.origin) + t * dvec3(ray.dir);
    const double alongRay = GammaDouble(8) * (glm::length(ray.origin) + fabs(t) * worldDirLength);
    surface->point = vec3(worldPoint);
    surface->pointError =
        Gamma(1) * Abs(surface->point) + vec3(float(stretch * (offSphere + roundedDir) + alongRay));
    surface->geomNormal = vec3(fromCentre);
}

RT_HD inline Surface MakeSurface(const RenderSceneView& scene, const Ray& ray,
                                 const SceneHit& hit) {
    const Instance& inst = scene.tlas.instances[hit.instance];
    const BlasView& blas = scene.tlas.blases[inst.blasId];
    Surface surface;
    vec3 ng, ns;
    if (blas.kind == GeometryKind::kTriangles) {
        const Triangle& tri = blas.triangles[hit.prim];
        const float b0 = 1.0f - hit.b1 - hit.b2;
        const vec3 p = b0 * tri.v0 + hit.b1 * tri.v1 + hit.b2 * tri.v2;
        const vec3 pError =
            Gamma(7) * (Abs(b0 * tri.v0) + Abs(hit.b1 * tri.v1) + Abs(hit.b2 * tri.v2));
        ng = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
        ns = ng;
        if (blas.normals) {
            ns = blas.normals[hit.prim].At(b0, hit.b1, hit.b2);
        }
        const Affine objectToWorld = inst.ObjectToWorld();
        surface.pointError = objectToWorld.PointError(p, pError);
        surface.point = objectToWorld.Point(p);
    } else {
        SphereSurfacePoint(blas.spheres[hit.prim], ray, inst, hit.t, &surface);
        ng = surface.geomNormal;
        ns = ng;
    }
    surface.geomNormal = glm::normalize(inst.NormalToWorld(ng));
    surface.shadingNormal = glm::normalize(inst.NormalToWorld(ns));
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
