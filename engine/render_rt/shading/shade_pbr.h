#pragma once
// Shading of a hit whose material is glTF's metallic-roughness (pbr_material.h): its textures,
// normal map, the BRDF of pbr_brdf.h under every light, emission, ambient light darkened by
// occlusion, and the weights of the mirror and refraction rays that carry the scene around it.
#include "engine/render_rt/shading/light_loop.h"
#include "engine/render_rt/shading/optics.h"
#include "engine/render_rt/shading/pbr_brdf.h"
#include "engine/render_rt/shading/pbr_material.h"
#include "engine/render_rt/shading/tangent_frame.h"

namespace rtrt {

// What a hit gives its ray (local, weighted by the ray's own weight) and the rays it continues in.
struct HitShading {
    vec3 local;
    vec3 normal;  // the shading normal secondary rays leave about
    vec3 reflectWeight;
    vec3 refractWeight;
    vec3 refracted;  // unit direction, where refractWeight is not zero
};

// The material's factors times its textures and the mesh's vertex colours at the hit (kernels with
// kFeatureTextures only), and the normal map's normal.
struct PbrInputs {
    PbrSample sample;
    float roughness;
    vec3 emissive;
    float occlusion;
    vec3 normal;
};

template <uint32_t kFeatures>
RT_HD inline PbrInputs PbrInputsAt(const RenderSceneView& scene, const SceneHit& hit,
                                   const Surface& s, const Material& m, const PbrMaterial& pm,
                                   float footprint) {
    PbrInputs in;
    in.sample.baseColor = pm.baseColor;
    in.sample.metallic = pm.metallic;
    vec3 dielectricF0 = pm.dielectricF0;
    in.sample.specularWeight = pm.specularWeight;
    in.sample.transmission = pm.transmission;
    in.roughness = pm.roughness;
    in.emissive = pm.emissive;
    in.occlusion = 1.0f;
    in.normal = s.shadingNormal;
    if constexpr ((kFeatures & kFeatureTextures) != 0) {
        const Instance& inst = scene.tlas.instances[hit.instance];
        const BlasView& blas = scene.tlas.blases[inst.blasId];
        if (blas.kind == GeometryKind::kTriangles && blas.uvs) {
            const TriangleUvs& uvs = blas.uvs[hit.prim];
            const vec2 uv = InterpolateUv(uvs, hit.b1, hit.b2);
            auto sample = [&](uint32_t texture) {
                return SampleTexture(scene.textures[texture], scene.texels, uv, footprint);
            };
            if (m.baseColorTexture != kNoTexture) in.sample.baseColor *= sample(m.baseColorTexture);
            if (pm.metallicRoughnessTexture != kNoTexture) {
                const vec3 mr = sample(pm.metallicRoughnessTexture);
                in.roughness *= mr.y;
                in.sample.metallic *= mr.z;
            }
            if (pm.emissiveTexture != kNoTexture) in.emissive *= sample(pm.emissiveTexture);
            if (pm.transmissionTexture != kNoTexture)
                in.sample.transmission *= sample(pm.transmissionTexture).x;
            if (pm.specularTexture != kNoTexture)
                in.sample.specularWeight *= sample(pm.specularTexture).x;
            if (pm.specularColorTexture != kNoTexture)
                dielectricF0 *= sample(pm.specularColorTexture);
            if (pm.occlusionTexture != kNoTexture)
                in.occlusion = 1.0f + pm.occlusionStrength * (sample(pm.occlusionTexture).x - 1.0f);
            if (pm.normalTexture != kNoTexture) {
                const vec3 t = sample(pm.normalTexture) * 2.0f - vec3(1.0f);
                const vec3 mapped(t.x * pm.normalScale, t.y * pm.normalScale, t.z);
                // A back face's normal is the front's reversed, bumps included.
                const vec3 front = s.frontFace ? s.shadingNormal : -s.shadingNormal;
                const vec3 n = blas.tangents
                                   ? NormalFromTangents(blas.tangents[hit.prim], hit.b1, hit.b2,
                                                        inst.ObjectToWorld(), front, mapped)
                                   : NormalFromMap(blas.triangles[hit.prim], uvs,
                                                   inst.ObjectToWorld(), front, mapped);
                in.normal = s.frontFace ? n : -n;
            }
        }
        if (blas.kind == GeometryKind::kTriangles && blas.colors)
            in.sample.baseColor *= blas.colors[hit.prim].At(hit.b1, hit.b2);
    }
    in.sample.dielectricF0 = glm::min(dielectricF0, vec3(1.0f));
    in.sample.alpha = GgxAlpha(in.roughness);
    return in;
}

template <uint32_t kFeatures, class Policy = TracePolicy>
RT_HD inline HitShading ShadePbr(const RenderSceneView& scene, const SceneHit& hit,
                                 const Surface& s, const Material& m, vec3 toViewer,
                                 float footprint, uint32_t* rays) {
    const PbrMaterial& pm = scene.pbrMaterials[m.pbrMaterial];
    const PbrInputs in = PbrInputsAt<kFeatures>(scene, hit, s, m, pm, footprint);
    const PbrSample& p = in.sample;
    const vec3 n = in.normal;
    HitShading out;
    out.normal = n;
    vec3 direct(0.0f);
    // Light colours are what a white Lambertian surface facing the light shows (light.h): the
    // illuminance is pi times the colour.
    ForEachLight<kFeatures, Policy>(scene, s, n, rays, [&](vec3 l, vec3 arriving, float nDotL) {
        direct += arriving * GltfBrdf(p, n, toViewer, l) * (kPi * nDotL);
    });
    const float nDotV = fmaxf(glm::dot(n, toViewer), 1e-4f);
    const vec3 specular = SpecularReflectance(p, nDotV);
    const float mirror = (kFeatures & kFeatureReflection) != 0 ? MirrorShare(in.roughness) : 0.0f;
    out.reflectWeight = mirror * specular;
    out.refractWeight = vec3(0.0f);
    out.refracted = vec3(0.0f);
    const vec3 ambient = pm.ambientLight * in.occlusion *
                         (DiffuseReflectance(p, nDotV) + (1.0f - mirror) * specular);
    out.local = in.emissive + ambient + direct;
    if constexpr ((kFeatures & kFeatureRefraction) != 0) {
        const float transmitted = p.transmission * (1.0f - p.metallic);
        if (transmitted > 0.0f && pm.thinWalled != 0) {
            // A thin wall: what passes its two faces goes on in the ray's own direction, less what
            // the BRDF's Fresnel layer reflects (the specification's fresnel_mix, so that
            // KHR_materials_specular's weight and colour apply as they do to the diffuse layer).
            const float fresnel = MaxComponent(DielectricFresnel(p, fabsf(glm::dot(toViewer, n))));
            out.refracted = -toViewer;
            out.refractWeight = transmitted * (1.0f - fresnel) * p.baseColor;
        } else if (transmitted > 0.0f) {
            const float eta = s.frontFace ? pm.ior : 1.0f / pm.ior;
            const float fresnel = FresnelDielectric(glm::dot(toViewer, n), eta);
            if (fresnel < 1.0f && Refract(toViewer, n, eta, &out.refracted))
                out.refractWeight = transmitted * (1.0f - fresnel) * p.baseColor;
            else
                out.reflectWeight += vec3(transmitted);  // total internal reflection
        }
    }
    return out;
}

}  // namespace rtrt
