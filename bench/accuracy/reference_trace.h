#pragma once
// The accuracy benchmark's reference pixel: trace.h's Blinn-Phong, shadows, reflection and
// Fresnel-weighted refraction with the same ray stack, in double precision from the camera ray
// to the shaded colour, and rays leaving surfaces by double error bounds (pbrt-v4 section 6.8).
// Samples lie where pixel_sample.h puts the float renderer's.
#include <algorithm>

#include "bench/accuracy/reference_geometry.h"
#include "engine/render_rt/pixel_sample.h"
#include "engine/render_rt/render_scene_view.h"

namespace rtrt::reference {

struct CameraFrameD {
    dvec3 origin, forward, right, up;
    double tanHalfFovY, aspect;
};

inline CameraFrameD MakeCameraFrameD(const Camera& camera, uint32_t width, uint32_t height) {
    CameraFrameD f;
    f.origin = dvec3(camera.position);
    f.forward = glm::normalize(dvec3(camera.forward));
    f.right = glm::normalize(glm::cross(f.forward, dvec3(camera.up)));
    f.up = glm::cross(f.right, f.forward);
    f.tanHalfFovY = std::tan(0.5 * double(camera.fovYDegrees) * M_PI / 180.0);
    f.aspect = double(width) / double(height);
    return f;
}

inline RayD PrimaryRayD(const CameraFrameD& f, double px, double py, uint32_t width,
                        uint32_t height) {
    const double sx = (2.0 * px / double(width) - 1.0) * f.tanHalfFovY * f.aspect;
    const double sy = (1.0 - 2.0 * py / double(height)) * f.tanHalfFovY;
    return {f.origin, glm::normalize(f.forward + sx * f.right + sy * f.up), HUGE_VAL};
}

struct SurfaceD {
    dvec3 point, pointError, geomNormal, shadingNormal;
    bool frontFace;
    uint32_t materialId;
};

// surface.h in double: the hit point with a bound on its error.
inline SurfaceD MakeSurfaceD(const TlasView& tlas, const RayD& ray, const HitD& hit) {
    const Instance& inst = tlas.instances[hit.instance];
    const BlasView& blas = tlas.blases[inst.blasId];
    dvec3 p, pError, ng, ns;
    if (blas.kind == GeometryKind::kTriangles) {
        const Triangle& tri = blas.triangles[hit.prim];
        const dvec3 v0(tri.v0), v1(tri.v1), v2(tri.v2);
        const double b0 = 1.0 - hit.b1 - hit.b2;
        p = b0 * v0 + hit.b1 * v1 + hit.b2 * v2;
        pError = GammaD(7) * (glm::abs(b0 * v0) + glm::abs(hit.b1 * v1) + glm::abs(hit.b2 * v2));
        ng = glm::cross(v1 - v0, v2 - v0);
        ns = ng;
        if (blas.normals) {
            const TriangleNormals& n = blas.normals[hit.prim];
            ns = b0 * dvec3(UnpackNormal(n.n0)) + hit.b1 * dvec3(UnpackNormal(n.n1)) +
                 hit.b2 * dvec3(UnpackNormal(n.n2));
        }
    } else {
        const Sphere& s = blas.spheres[hit.prim];
        const RayD objectRay = ToObjectSpaceD(ray, inst);
        const dvec3 centre(s.center);
        const dvec3 fromCentre = objectRay.origin + hit.t * objectRay.dir - centre;
        p = centre + fromCentre * (double(s.radius) / glm::length(fromCentre));
        pError = GammaD(5) * glm::abs(p);
        ng = p - centre;
        ns = ng;
    }
    SurfaceD surface;
    // Affine::PointError in double.
    const glm::dmat3 linear = LinearD(inst);
    const dvec3 position(inst.Position());
    for (int i = 0; i < 3; ++i) {
        const dvec3 r(linear[0][i], linear[1][i], linear[2][i]);
        const double roundOff = std::fabs(r.x * p.x) + std::fabs(r.y * p.y) + std::fabs(r.z * p.z) +
                                std::fabs(position[i]);
        const double carried =
            std::fabs(r.x) * pError.x + std::fabs(r.y) * pError.y + std::fabs(r.z) * pError.z;
        surface.pointError[i] = GammaD(3) * roundOff + (1.0 + GammaD(3)) * carried;
    }
    surface.point = linear * p + position;
    const glm::dmat3 normalMatrix = glm::transpose(InverseLinearD(inst));
    surface.geomNormal = glm::normalize(normalMatrix * ng);
    surface.shadingNormal = glm::normalize(normalMatrix * ns);
    surface.frontFace = glm::dot(surface.geomNormal, ray.dir) < 0.0;
    if (!surface.frontFace) surface.geomNormal = -surface.geomNormal;
    if (glm::dot(surface.shadingNormal, surface.geomNormal) < 0.0)
        surface.shadingNormal = -surface.shadingNormal;
    surface.materialId = inst.materialId;
    return surface;
}

// OffsetRayOrigin (float_bounds.h) in double.
inline RayD SpawnRayD(const SurfaceD& s, dvec3 dir, double tMax = HUGE_VAL) {
    dvec3 offset = glm::dot(glm::abs(s.geomNormal), s.pointError) * s.geomNormal;
    if (glm::dot(dir, s.geomNormal) < 0.0) offset = -offset;
    dvec3 po = s.point + offset;
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > 0.0) po[i] = std::nextafter(po[i], HUGE_VAL);
        if (offset[i] < 0.0) po[i] = std::nextafter(po[i], -HUGE_VAL);
    }
    return {po, dir, tMax};
}

// optics.h in double.
inline double FresnelDielectricD(double cosThetaI, double eta) {
    cosThetaI = std::clamp(cosThetaI, -1.0, 1.0);
    if (cosThetaI < 0.0) {
        eta = 1.0 / eta;
        cosThetaI = -cosThetaI;
    }
    const double sin2ThetaT = (1.0 - cosThetaI * cosThetaI) / (eta * eta);
    if (sin2ThetaT >= 1.0) return 1.0;
    const double cosThetaT = std::sqrt(std::fmax(0.0, 1.0 - sin2ThetaT));
    const double rParallel = (eta * cosThetaI - cosThetaT) / (eta * cosThetaI + cosThetaT);
    const double rPerpendicular = (cosThetaI - eta * cosThetaT) / (cosThetaI + eta * cosThetaT);
    return 0.5 * (rParallel * rParallel + rPerpendicular * rPerpendicular);
}
inline bool RefractD(dvec3 wi, dvec3 n, double eta, dvec3* wt) {
    const double cosThetaI = glm::dot(n, wi);
    const double sin2ThetaT = std::fmax(0.0, 1.0 - cosThetaI * cosThetaI) / (eta * eta);
    if (sin2ThetaT >= 1.0) return false;
    const double cosThetaT = std::sqrt(1.0 - sin2ThetaT);
    *wt = -wi / eta + (cosThetaI / eta - cosThetaT) * n;
    return true;
}

inline dvec3 ShadeLocalD(const RenderSceneView& scene, const SurfaceD& s, const Material& m,
                         dvec3 toViewer) {
    dvec3 color(m.ambient);
    for (uint32_t i = 0; i < scene.lightCount; ++i) {
        const Light& light = scene.lights[i];
        const bool directional = light.type == LightType::kDirectional;
        const dvec3 toLight = directional ? dvec3(light.vector) : dvec3(light.vector) - s.point;
        const dvec3 l = glm::normalize(toLight);
        const double nDotL = glm::dot(s.shadingNormal, l);
        if (nDotL <= 0.0 || glm::dot(s.geomNormal, l) <= 0.0) continue;
        HitD unused;
        const double tMax = directional ? HUGE_VAL : std::nextafter(1.0, 0.0);
        if (TraceSceneD<Query::kOccluded>(scene.tlas, SpawnRayD(s, toLight, tMax), &unused))
            continue;
        const dvec3 h = glm::normalize(l + toViewer);
        const double nDotH = std::fmax(0.0, glm::dot(s.shadingNormal, h));
        color += dvec3(light.color) * (dvec3(m.diffuse) * nDotL +
                                       dvec3(m.specular) * std::pow(nDotH, double(m.shininess)));
    }
    return color;
}

// TraceRay's ray stack (trace.h) with every effect on; maxDepth as in RenderSceneView.
inline dvec3 TraceRayD(const RenderSceneView& scene, const RayD& primary) {
    struct PendingRay {
        RayD ray;
        dvec3 weight;
        uint32_t depth;
    };
    PendingRay stack[kMaxRayDepth + 1];
    uint32_t stackSize = 0;
    stack[stackSize++] = {primary, dvec3(1.0), 1};
    dvec3 color(0.0);
    while (stackSize > 0) {
        const PendingRay pending = stack[--stackSize];
        HitD hit;
        if (!TraceSceneD<Query::kIntersect>(scene.tlas, pending.ray, &hit)) {
            color += pending.weight * dvec3(scene.background);
            continue;
        }
        const SurfaceD s = MakeSurfaceD(scene.tlas, pending.ray, hit);
        const Material& m = scene.materials[s.materialId];
        const dvec3 toViewer = -glm::normalize(pending.ray.dir);
        double reflectWeight = m.reflectivity, refractWeight = 0.0;
        dvec3 refracted(0.0);
        if (m.transmissivity > 0.0f) {
            const double eta = s.frontFace ? double(m.ior) : 1.0 / double(m.ior);
            const double fresnel = FresnelDielectricD(glm::dot(toViewer, s.shadingNormal), eta);
            if (fresnel < 1.0 && RefractD(toViewer, s.shadingNormal, eta, &refracted)) {
                refractWeight = m.transmissivity * (1.0 - fresnel);
                reflectWeight += m.transmissivity * fresnel;
            } else {
                reflectWeight += m.transmissivity;
            }
        }
        const double localWeight =
            std::fmax(0.0, 1.0 - double(m.reflectivity) - double(m.transmissivity));
        if (localWeight > 0.0)
            color += pending.weight * localWeight * ShadeLocalD(scene, s, m, toViewer);
        if (pending.depth >= scene.maxDepth) continue;
        if (reflectWeight > 0.0) {
            const dvec3 dir =
                -toViewer + 2.0 * glm::dot(toViewer, s.shadingNormal) * s.shadingNormal;
            if (glm::dot(dir, s.geomNormal) > 0.0)
                stack[stackSize++] = {SpawnRayD(s, dir), pending.weight * reflectWeight,
                                      pending.depth + 1};
        }
        if (refractWeight > 0.0)
            stack[stackSize++] = {SpawnRayD(s, refracted), pending.weight * refractWeight,
                                  pending.depth + 1};
    }
    return color;
}

// The shaded pixel: the average of samplesPerPixel stratified samples.
inline dvec3 ReferencePixel(const RenderSceneView& scene, const CameraFrameD& camera, uint32_t x,
                            uint32_t y) {
    const uint32_t n = StrataPerSide(scene.samplesPerPixel);
    dvec3 sum(0.0);
    for (uint32_t s = 0; s < n * n; ++s) {
        const vec2 at = PixelSample(x, y, s, n);
        sum += TraceRayD(scene, PrimaryRayD(camera, double(x) + at.x, double(y) + at.y, scene.width,
                                            scene.height));
    }
    return sum / double(n * n);
}

}  // namespace rtrt::reference
