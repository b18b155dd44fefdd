#pragma once
// The per-pixel tracing body shared by the CPU and CUDA back ends. Reflection and refraction
// follow an explicit ray stack instead of recursion (the original paper's iterative ray queue):
// a ray's secondary rays are pushed with the weight they contribute, and the pixel is the sum of
// weight * local shading over every ray popped.
#include "engine/render_rt/optics.h"
#include "engine/render_rt/trace_policy.h"

namespace rtrt {

struct PixelResult {
    vec3 color;
    vec3 normal;           // primary hit's shading normal, zero on a miss
    float depth;           // primary hit distance, infinity on a miss
    TraversalStats stats;  // primary ray's binary-BVH traversal, when countTraversal
    uint32_t rays;         // rays traced for this pixel: primary, shadow and secondary
};

// The scene traversal a specialisation uses: on the GPU, scenes of many instances take the single
// loop over both levels; otherwise (and always on the CPU) the nested form. Both take the
// policy's primitive tests (trace_policy.h).
template <uint32_t kFeatures, class Policy = TracePolicy>
RT_HD inline bool TraceIntersect(const TlasView& tlas, const Ray& ray, SceneHit* hit,
                                 TraversalStats* stats) {
#if defined(RT_ON_GPU)
    if constexpr ((kFeatures & kFeatureManyInstances) != 0) {
        float tMax = ray.tMax;
        return TraverseTwoLevel<Query::kIntersect, Policy>(tlas, ray, tMax, hit, stats);
    }
#endif
    return IntersectScene<Policy>(tlas, ray, hit, stats);
}

template <uint32_t kFeatures, class Policy = TracePolicy>
RT_HD inline bool TraceOccluded(const TlasView& tlas, const Ray& ray) {
#if defined(RT_ON_GPU)
    if constexpr ((kFeatures & kFeatureManyInstances) != 0) {
        float tMax = ray.tMax;
        return TraverseTwoLevel<Query::kOccluded, Policy>(tlas, ray, tMax, nullptr, nullptr);
    }
#endif
    return OccludedScene<Policy>(tlas, ray);
}

// The material at a hit, its base-colour texture applied (only in kernels with kFeatureTextures):
// the sample multiplies diffuse and ambient. scratch holds the textured copy.
template <uint32_t kFeatures>
RT_HD inline const Material& MaterialAt(const RenderSceneView& scene, const SceneHit& hit,
                                        uint32_t materialId, Material* scratch) {
    const Material& m = scene.materials[materialId];
    if constexpr ((kFeatures & kFeatureTextures) != 0) {
        if (m.baseColorTexture == kNoTexture) return m;
        const Instance& inst = scene.tlas.instances[hit.instance];
        const BlasView& blas = scene.tlas.blases[inst.blasId];
        if (blas.kind != GeometryKind::kTriangles || !blas.uvs) return m;
        const vec2 uv = InterpolateUv(blas.uvs[hit.prim], hit.b1, hit.b2);
        const vec3 sample = SampleTexture(scene.textures[m.baseColorTexture], scene.texels, uv);
        *scratch = m;
        scratch->diffuse *= sample;
        scratch->ambient *= sample;
        return *scratch;
    }
    return m;
}

// Blinn-Phong for one surface point with hard shadows.
template <uint32_t kFeatures, class Policy = TracePolicy>
RT_HD inline vec3 ShadeLocal(const RenderSceneView& scene, const Surface& s, const Material& m,
                             vec3 toViewer, uint32_t* rays) {
    vec3 color = m.ambient;
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
        const float nDotL = glm::dot(s.shadingNormal, l);
        if (nDotL <= 0.0f || glm::dot(s.geomNormal, l) <= 0.0f) continue;
        if constexpr ((kFeatures & kFeatureShadows) != 0) {
            ++*rays;
            if (TraceOccluded<kFeatures, Policy>(scene.tlas,
                                                 Policy::SpawnRay(s, toLight, shadowTMax)))
                continue;
        }
        const vec3 h = glm::normalize(l + toViewer);
        const float nDotH = fmaxf(0.0f, glm::dot(s.shadingNormal, h));
        color += light.color * (m.diffuse * nDotL + m.specular * powf(nDotH, m.shininess));
    }
    return color;
}

// Everything one primary ray brings back.
template <uint32_t kFeatures, class Policy = TracePolicy>
RT_HD inline PixelResult TraceRay(const RenderSceneView& scene, const Ray& primaryRay,
                                  bool countTraversal = false) {
    struct PendingRay {
        Ray ray;
        vec3 weight;
        uint32_t depth;
    };
    PendingRay stack[kMaxRayDepth + 1];
    uint32_t stackSize = 0;
    stack[stackSize++] = {primaryRay, vec3(1.0f), 1};

    PixelResult result{vec3(0.0f), vec3(0.0f), kInfinity, {}, 0};
    bool primary = true;
    while (stackSize > 0) {
        const PendingRay pending = stack[--stackSize];
        SceneHit hit;
        ++result.rays;
        const bool found = TraceIntersect<kFeatures, Policy>(
            scene.tlas, pending.ray, &hit, primary && countTraversal ? &result.stats : nullptr);
        if (!found) {
            result.color += pending.weight * scene.background;
            primary = false;
            continue;
        }
        const Surface s = MakeSurface(scene, pending.ray, hit);
        if (primary) {
            result.depth = hit.t * glm::length(pending.ray.dir);
            result.normal = s.shadingNormal;
            primary = false;
        }
        Material textured;
        const Material& m = MaterialAt<kFeatures>(scene, hit, s.materialId, &textured);
        const vec3 toViewer = -glm::normalize(pending.ray.dir);
        float reflectWeight = (kFeatures & kFeatureReflection) ? m.reflectivity : 0.0f;
        float refractWeight = 0.0f;
        vec3 refracted(0.0f);
        if constexpr ((kFeatures & kFeatureRefraction) != 0) {
            if (m.transmissivity > 0.0f) {
                // Relative index across the boundary in the direction of travel.
                const float eta = s.frontFace ? m.ior : 1.0f / m.ior;
                const float cosI = glm::dot(toViewer, s.shadingNormal);
                const float fresnel = FresnelDielectric(cosI, eta);
                if (fresnel < 1.0f && Refract(toViewer, s.shadingNormal, eta, &refracted)) {
                    refractWeight = m.transmissivity * (1.0f - fresnel);
                    reflectWeight += m.transmissivity * fresnel;
                } else {
                    reflectWeight += m.transmissivity;  // total internal reflection
                }
            }
        }
        const float localWeight = fmaxf(0.0f, 1.0f - m.reflectivity - m.transmissivity);
        if (localWeight > 0.0f)
            result.color += pending.weight * localWeight *
                            ShadeLocal<kFeatures, Policy>(scene, s, m, toViewer, &result.rays);
        if (pending.depth >= scene.maxDepth) continue;
        if (reflectWeight > 0.0f) {
            const vec3 dir = Reflect(toViewer, s.shadingNormal);
            if (glm::dot(dir, s.geomNormal) > 0.0f)
                stack[stackSize++] = {Policy::SpawnRay(s, dir), pending.weight * reflectWeight,
                                      pending.depth + 1};
        }
        if (refractWeight > 0.0f) {
            stack[stackSize++] = {Policy::SpawnRay(s, refracted), pending.weight * refractWeight,
                                  pending.depth + 1};
        }
    }
    return result;
}

}  // namespace rtrt
