#pragma once
// The direct-light loop both shading models share: for each light above the surface and not in
// shadow, its unit direction, the colour that reaches the point and the cosine at the shading
// normal.
#include "engine/render_rt/scene_trace.h"
#include "engine/render_rt/shading/light.h"

namespace rtrt {

// Calls lit(l, arriving, nDotL) for every light that reaches surface point s with shading normal
// n; counts the shadow rays in *rays.
template <uint32_t kFeatures, class Policy, class Lit>
RT_HD inline void ForEachLight(const RenderSceneView& scene, const Surface& s, vec3 n,
                               uint32_t* rays, Lit&& lit) {
    for (uint32_t i = 0; i < scene.lightCount; ++i) {
        const Light& light = scene.lights[i];
        vec3 toLight;
        float shadowTMax;
        if (light.type == LightType::kDirectional) {
            toLight = light.vector;
            shadowTMax = kInfinity;
        } else {
            toLight = light.vector - s.point;  // unnormalised: the light sits at t = 1
            shadowTMax = NextFloatDown(1.0f);
        }
        const vec3 l = glm::normalize(toLight);
        const float nDotL = glm::dot(n, l);
        // Written so that NaN fails too: a point light exactly at the point has no direction.
        if (!(nDotL > 0.0f) || !(glm::dot(s.geomNormal, l) > 0.0f)) continue;
        // What arrives is worked out after the shadow ray, from the light's record again: a
        // value kept across the traversal cost the Blinn-Phong kernels an occupancy step
        // (bench/results/pbr-h200-2026-12-02.txt). Only PBR kernels skip the shadow rays of
        // lights beyond their range or cone.
        if constexpr ((kFeatures & kFeaturePbr) != 0) {
            if (LightAttenuates(light) && !(LightAttenuation(light, toLight, l) > 0.0f)) continue;
        }
        if constexpr ((kFeatures & kFeatureShadows) != 0) {
            ++*rays;
            if (TraceOccluded<kFeatures, Policy>(scene.tlas,
                                                 Policy::SpawnRay(s, toLight, shadowTMax)))
                continue;
        }
        vec3 arriving = light.color;
        if (LightAttenuates(light)) arriving *= LightAttenuation(light, light.vector - s.point, l);
        lit(l, arriving, nDotL);
    }
}

}  // namespace rtrt
