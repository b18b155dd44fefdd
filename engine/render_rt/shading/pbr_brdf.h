#pragma once
// glTF 2.0's metallic-roughness BRDF (specification, appendix B): Trowbridge-Reitz (GGX) normal
// distribution, height-correlated Smith visibility (Heitz 2014), Schlick's Fresnel; Lambert
// diffuse under the dielectric's Fresnel layer; metals tint the specular by the base colour;
// KHR_materials_specular scales and tints the dielectric's F0.
#include "engine/core/math.h"

namespace rtrt {

// The smallest GGX alpha: a roughness-0 surface still gives point lights a (tiny) highlight.
inline constexpr float kMinGgxAlpha = 1e-3f;

// A shading point's material after its textures.
struct PbrSample {
    vec3 baseColor;
    float metallic;
    float alpha;  // GGX alpha, roughness^2
    vec3 dielectricF0;
    float specularWeight;
    float transmission;  // the dielectric's diffuse share that transmits instead (refraction)
};

RT_HD inline float GgxAlpha(float roughness) { return fmaxf(roughness * roughness, kMinGgxAlpha); }

// D(h): the GGX distribution of microfacet normals at cos(n, h).
RT_HD inline float GgxDistribution(float nDotH, float alpha) {
    const float a2 = alpha * alpha;
    const float d = nDotH * nDotH * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * d * d);
}

// V = G2 / (4 |n.l| |n.v|) for the height-correlated Smith masking-shadowing of GGX.
RT_HD inline float SmithGgxVisibility(float nDotL, float nDotV, float alpha) {
    const float a2 = alpha * alpha;
    const float viewTerm = nDotL * sqrtf(nDotV * nDotV * (1.0f - a2) + a2);
    const float lightTerm = nDotV * sqrtf(nDotL * nDotL * (1.0f - a2) + a2);
    const float sum = viewTerm + lightTerm;
    return sum > 0.0f ? 0.5f / sum : 0.0f;
}

// (1 - cos)^5, Schlick's Fresnel weight.
RT_HD inline float SchlickWeight(float cosTheta) {
    const float m = fminf(fmaxf(1.0f - fabsf(cosTheta), 0.0f), 1.0f);
    const float m2 = m * m;
    return m2 * m2 * m;
}

RT_HD inline vec3 SchlickFresnel(vec3 f0, float cosTheta) {
    return f0 + (vec3(1.0f) - f0) * SchlickWeight(cosTheta);
}

// The dielectric's Fresnel layer, KHR_materials_specular's weight included.
RT_HD inline vec3 DielectricFresnel(const PbrSample& p, float cosTheta) {
    return p.specularWeight * SchlickFresnel(p.dielectricF0, cosTheta);
}

// The dielectric's diffuse albedo at the viewing angle: what its Fresnel layer lets through, less
// what transmits (KHR_materials_transmission).
RT_HD inline vec3 DiffuseLayer(const PbrSample& p, float nDotV) {
    return (1.0f - p.transmission) * (1.0f - MaxComponent(DielectricFresnel(p, nDotV))) *
           p.baseColor;
}

// f(l, v) for unit vectors n, v (toward the viewer) and l (toward the light), both above the
// surface; multiply by the light's irradiance-scale colour and n.l.
RT_HD inline vec3 GltfBrdf(const PbrSample& p, vec3 n, vec3 v, vec3 l) {
    const vec3 h = glm::normalize(l + v);
    const float nDotL = fmaxf(glm::dot(n, l), 0.0f);
    const float nDotV = fmaxf(glm::dot(n, v), 1e-4f);
    const float nDotH = fmaxf(glm::dot(n, h), 0.0f);
    const float vDotH = glm::dot(v, h);
    const float specular =
        GgxDistribution(nDotH, p.alpha) * SmithGgxVisibility(nDotL, nDotV, p.alpha);
    // The diffuse layer keeps what the Fresnel layer lets through at the viewing angle, not at
    // v.h as the specification's fresnel_mix has it: with v.h a white rough dielectric reflects
    // up to 1.14 of the light at grazing angles; with n.v it stays under 1 (pbr_test.cpp).
    const vec3 dielectric =
        DiffuseLayer(p, nDotV) * (1.0f / kPi) + DielectricFresnel(p, vDotH) * specular;
    const vec3 metal = SchlickFresnel(p.baseColor, vDotH) * specular;
    return glm::mix(dielectric, metal, p.metallic);
}

// What a smooth surface reflects of the scene around it, at the viewing angle: the specular
// Fresnel of the BRDF with h = n (the mirror direction's half vector), metal and dielectric mixed.
RT_HD inline vec3 SpecularReflectance(const PbrSample& p, float nDotV) {
    return glm::mix(DielectricFresnel(p, nDotV), SchlickFresnel(p.baseColor, nDotV), p.metallic);
}

// The diffuse albedo of the whole material at the viewing angle (metals have none).
RT_HD inline vec3 DiffuseReflectance(const PbrSample& p, float nDotV) {
    return (1.0f - p.metallic) * DiffuseLayer(p, nDotV);
}

// The share of the specular reflection traced as a mirror ray: 1 for a perfectly smooth surface,
// falling to 0 at roughness 0.5; rougher surfaces reflect lights only (through GgxDistribution),
// and the scene around them as ambient light, so that no noise appears.
RT_HD inline float MirrorShare(float roughness) {
    const float s = fmaxf(1.0f - 2.0f * roughness, 0.0f);
    return s * s;
}

}  // namespace rtrt
