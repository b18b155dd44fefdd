#pragma once
// The ray offset as an accuracy variant (accuracy_variant.h): by default origins move off the
// surface by its error bound (surface.h, pbrt-v4); kAccuracyFixedEpsilon moves them a fixed
// 1e-4 along the normal, the common shortcut, which is too little far from the origin (acne)
// and too much beside thin or small geometry (leaks).
#include "bench/accuracy/accuracy_variant.h"
#include "engine/render_rt/surface.h"

namespace rtrt {

inline constexpr float kFixedRayEpsilon = 1e-4f;

template <uint32_t kAccuracy>
RT_HD inline Ray SpawnRayAs(const Surface& s, vec3 dir, float tMax = kInfinity) {
    Ray r = SpawnRay(s, dir, tMax);
    if constexpr ((kAccuracy & kAccuracyFixedEpsilon) != 0) {
        const float side = glm::dot(dir, s.geomNormal) < 0.0f ? -1.0f : 1.0f;
        r.origin = s.point + (side * kFixedRayEpsilon) * s.geomNormal;
    }
    return r;
}

}  // namespace rtrt
