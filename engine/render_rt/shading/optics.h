#pragma once
// Reflection, refraction and the exact Fresnel equations for dielectrics (pbrt-v4 FrDielectric).
#include "engine/core/math.h"

namespace rtrt {

RT_HD inline vec3 Reflect(vec3 wo, vec3 n) { return -wo + 2.0f * glm::dot(wo, n) * n; }

// Unpolarised Fresnel reflectance at a boundary of relative index eta = n_transmitted /
// n_incident; cosThetaI < 0 means the light arrives from the other side. 1 under total internal
// reflection.
RT_HD inline float FresnelDielectric(float cosThetaI, float eta) {
    cosThetaI = fminf(fmaxf(cosThetaI, -1.0f), 1.0f);
    if (cosThetaI < 0.0f) {
        eta = 1.0f / eta;
        cosThetaI = -cosThetaI;
    }
    const float sin2ThetaT = (1.0f - cosThetaI * cosThetaI) / (eta * eta);
    if (sin2ThetaT >= 1.0f) return 1.0f;
    const float cosThetaT = sqrtf(fmaxf(0.0f, 1.0f - sin2ThetaT));
    const float rParallel = (eta * cosThetaI - cosThetaT) / (eta * cosThetaI + cosThetaT);
    const float rPerpendicular = (cosThetaI - eta * cosThetaT) / (cosThetaI + eta * cosThetaT);
    return 0.5f * (rParallel * rParallel + rPerpendicular * rPerpendicular);
}

// Refracts wi (pointing away from the surface, on n's side) through a boundary of relative
// index eta; false under total internal reflection.
RT_HD inline bool Refract(vec3 wi, vec3 n, float eta, vec3* wt) {
    const float cosThetaI = glm::dot(n, wi);
    const float sin2ThetaT = fmaxf(0.0f, 1.0f - cosThetaI * cosThetaI) / (eta * eta);
    if (sin2ThetaT >= 1.0f) return false;
    const float cosThetaT = sqrtf(1.0f - sin2ThetaT);
    *wt = -wi / eta + (cosThetaI / eta - cosThetaT) * n;
    return true;
}

}  // namespace rtrt
