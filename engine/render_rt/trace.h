#pragma once
// The per-pixel tracing body shared by the CPU and CUDA back ends. Reflection and refraction
// follow an explicit ray stack instead of recursion (the original paper's iterative ray queue):
// a ray's secondary rays are pushed with the weight they contribute, and the pixel is the sum of
// weight * local shading over every ray popped.
#include "engine/render_rt/pixel_sample.h"
#include "engine/render_rt/shading/light_loop.h"
#include "engine/render_rt/shading/optics.h"
#include "engine/render_rt/shading/shade_pbr.h"

namespace rtrt {

struct PixelResult {
    vec3 color;
    vec3 normal;           // primary hit's shading normal, zero on a miss
    float depth;           // primary hit distance, infinity on a miss
    TraversalStats stats;  // primary ray's binary-BVH traversal, when countTraversal
    uint32_t rays;         // rays traced for this pixel: primary, shadow and secondary
};

// The angle a pixel's ray cone spreads by: the image plane's height over its rows, and over the
// strata per side when a pixel takes several samples.
RT_HD inline float PixelSpreadAngle(const RenderSceneView& scene) {
    return 2.0f * scene.camera.tanHalfFovY /
           (float(scene.height) * float(StrataPerSide(scene.samplesPerPixel)));
}

// log2 of the footprint in texture coordinates of a ray cone coneWidth wide where it hits a
// triangle (TextureFootprint), for mip level selection; very small where there is no triangle.
RT_HD inline float HitFootprint(const RenderSceneView& scene, const SceneHit& hit, const Surface& s,
                                const Ray& ray, float coneWidth) {
    const Instance& inst = scene.tlas.instances[hit.instance];
    const BlasView& blas = scene.tlas.blases[inst.blasId];
    if (blas.kind != GeometryKind::kTriangles || !blas.uvs) return -1e30f;
    const Triangle& tri = blas.triangles[hit.prim];
    const Affine objectToWorld = inst.ObjectToWorld();
    const vec3 e1 = objectToWorld.Vector(tri.v1 - tri.v0);
    const vec3 e2 = objectToWorld.Vector(tri.v2 - tri.v0);
    return TextureFootprint(blas.uvs[hit.prim], e1, e2, coneWidth,
                            glm::dot(s.geomNormal, glm::normalize(ray.dir)));
}

// The material at a hit, its base-colour texture and the mesh's vertex colours applied (only in
// kernels with kFeatureTextures): they multiply diffuse and ambient. scratch holds the tinted
// copy. footprint selects the mip level (HitFootprint).
template <uint32_t kFeatures>
RT_HD inline const Material& MaterialAt(const RenderSceneView& scene, const SceneHit& hit,
                                        uint32_t materialId, float footprint, Material* scratch) {
    const Material& m = scene.materials[materialId];
    if constexpr ((kFeatures & kFeatureTextures) != 0) {
        const Instance& inst = scene.tlas.instances[hit.instance];
        const BlasView& blas = scene.tlas.blases[inst.blasId];
        if (blas.kind != GeometryKind::kTriangles) return m;
        const bool textured = m.baseColorTexture != kNoTexture && blas.uvs;
        if (!textured && !blas.colors) return m;
        vec3 tint(1.0f);
        if (textured) {
            const vec2 uv = InterpolateUv(blas.uvs[hit.prim], hit.b1, hit.b2);
            tint = SampleTexture(scene.textures[m.baseColorTexture], scene.texels, uv, footprint);
        }
        if (blas.colors) tint *= blas.colors[hit.prim].At(hit.b1, hit.b2);
        *scratch = m;
        scratch->diffuse *= tint;
        scratch->ambient *= tint;
        return *scratch;
    }
    return m;
}

// Blinn-Phong for one surface point with hard shadows.
template <uint32_t kFeatures, class Policy = TracePolicy>
RT_HD inline vec3 ShadeLocal(const RenderSceneView& scene, const Surface& s, const Material& m,
                             vec3 toViewer, uint32_t* rays) {
    vec3 color = m.ambient;
    ForEachLight<kFeatures, Policy>(
        scene, s, s.shadingNormal, rays, [&](vec3 l, vec3 arriving, float nDotL) {
            const vec3 h = glm::normalize(l + toViewer);
            const float nDotH = fmaxf(0.0f, glm::dot(s.shadingNormal, h));
            color += arriving * (m.diffuse * nDotL + m.specular * powf(nDotH, m.shininess));
        });
    return color;
}

// A copy of a ray made float by float. g++ copies a whole Ray with one 32-byte load, which stalls
// when the ray was just stored a float at a time (the CPU cannot forward several stores to one
// load); copies of the stores' size are forwarded by the compiler instead.
RT_HD inline Ray CopyByFields(const Ray& r) {
    Ray c;
    c.origin.x = r.origin.x;
    c.origin.y = r.origin.y;
    c.origin.z = r.origin.z;
    c.tMax = r.tMax;
    c.dir.x = r.dir.x;
    c.dir.y = r.dir.y;
    c.dir.z = r.dir.z;
    c.pad = r.pad;
    return c;
}

// Everything one primary ray brings back. Forced inline on the host, so that the primary ray
// reaches it in registers rather than through the caller's memory.
template <uint32_t kFeatures, class Policy = TracePolicy>
RT_HOST_ALWAYS_INLINE RT_HD inline PixelResult TraceRay(const RenderSceneView& scene,
                                                        const Ray& primaryRay,
                                                        bool countTraversal = false) {
    struct PendingRay {
        Ray ray;
        vec3 weight;
        uint32_t depth;
    };
    PendingRay stack[kMaxRayDepth + 1];
    // From the camera to each pending ray's origin, for texture ray cones: kept apart so that
    // kernels without textures keep the stack entry they had (a longer one slowed deep
    // refraction down: bench/results/pbr-h200-2026-12-02.txt).
    constexpr bool kCones = (kFeatures & kFeatureTextures) != 0;
    float pathLengths[kCones ? kMaxRayDepth + 1 : 1];
    uint32_t stackSize = 0;
    auto push = [&](const Ray& ray, vec3 weight, uint32_t depth, float pathLength) {
        if constexpr (kCones) pathLengths[stackSize] = pathLength;
        stack[stackSize++] = {ray, weight, depth};
    };
#if defined(__CUDA_ARCH__)
    // On the GPU the primary ray waits on the stack too. Taken in hand as on the CPU it traced
    // faster, but the nested and single-loop kernels then no longer computed the same bits (FMA
    // contraction, most likely), which tests of the traversal forms require
    // (bench/results/primary-ray-in-hand-h100-2026-12-07.txt).
    push(primaryRay, vec3(1.0f), 1, 0.0f);
#endif

    PixelResult result{vec3(0.0f), vec3(0.0f), kInfinity, {}, 0};
#if defined(__CUDA_ARCH__)
    bool primary = true;
    while (stackSize > 0) {
        const PendingRay pending = stack[--stackSize];
        float pathLength = 0.0f;
        if constexpr (kCones) pathLength = pathLengths[stackSize];
#else
    // The primary ray is in hand from the start; only secondary rays wait on the stack. Every
    // pixel, most of which shoot no secondary ray, so skips a store to the stack that the wider
    // load of its pop then waited on (store forwarding fails).
    PendingRay pending{CopyByFields(primaryRay), vec3(1.0f), 1};
    float pathLength = 0.0f;
    for (bool primary = true;; primary = false) {
        if (!primary) {
            if (stackSize == 0) break;
            pending = stack[--stackSize];
            if constexpr (kCones) pathLength = pathLengths[stackSize];
        }
#endif
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
        const vec3 toViewer = -glm::normalize(pending.ray.dir);
        float footprint = 0.0f;
        if constexpr (kCones) {
            pathLength += hit.t * glm::length(pending.ray.dir);
            footprint =
                HitFootprint(scene, hit, s, pending.ray, pathLength * PixelSpreadAngle(scene));
        }
        if constexpr ((kFeatures & kFeaturePbr) != 0) {
            const Material& material = scene.materials[s.materialId];
            if (material.pbrMaterial != kNoPbrMaterial) {
                const HitShading h = ShadePbr<kFeatures, Policy>(scene, hit, s, material, toViewer,
                                                                 footprint, &result.rays);
                result.color += pending.weight * h.local;
                if (pending.depth >= scene.maxDepth) continue;
                if (MaxComponent(h.reflectWeight) > 0.0f) {
                    const vec3 dir = Reflect(toViewer, h.normal);
                    if (glm::dot(dir, s.geomNormal) > 0.0f)
                        push(Policy::SpawnRay(s, dir), pending.weight * h.reflectWeight,
                             pending.depth + 1, pathLength);
                }
                if (MaxComponent(h.refractWeight) > 0.0f)
                    push(Policy::SpawnRay(s, h.refracted), pending.weight * h.refractWeight,
                         pending.depth + 1, pathLength);
                continue;
            }
        }
        Material textured;
        const Material& m = MaterialAt<kFeatures>(scene, hit, s.materialId, footprint, &textured);
        float reflectWeight = (kFeatures & kFeatureReflection) ? m.reflectivity : 0.0f;
        float refractWeight = 0.0f;
        vec3 refracted(0.0f);
        if constexpr ((kFeatures & kFeatureRefraction) != 0) {
            if (m.transmissivity > 0.0f) {
                // Relative index across the boundary in the direction of travel; a thin wall is
                // entered and left at once, unbent.
                const bool thin = m.thinWalled != 0;
                const float eta = s.frontFace || thin ? m.ior : 1.0f / m.ior;
                const float cosI = thin ? fabsf(glm::dot(toViewer, s.shadingNormal))
                                        : glm::dot(toViewer, s.shadingNormal);
                const float fresnel = FresnelDielectric(cosI, eta);
                if (thin) refracted = -toViewer;
                if (fresnel < 1.0f &&
                    (thin || Refract(toViewer, s.shadingNormal, eta, &refracted))) {
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
                push(Policy::SpawnRay(s, dir), pending.weight * reflectWeight, pending.depth + 1,
                     pathLength);
        }
        if (refractWeight > 0.0f) {
            push(Policy::SpawnRay(s, refracted), pending.weight * refractWeight, pending.depth + 1,
                 pathLength);
        }
    }
    return result;
}

}  // namespace rtrt
