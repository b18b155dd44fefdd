#pragma once
// glTF 2.0's metallic-roughness material, beside rtrt's Blinn-Phong (material.h): a Material whose
// pbrMaterial names one of these is shaded by pbr_brdf.h. Texture slots index the scene's texture
// table (each record carries its own KHR_texture_transform); kNoTexture leaves the factor alone.
#include "engine/render_rt/shading/material.h"

namespace rtrt {

// 112 bytes.
struct PbrMaterial {
    vec3 baseColor{1.0f};  // linear; times the base-colour texture (Material::baseColorTexture)
    float metallic = 1.0f;
    vec3 emissive{0.0f};     // linear radiance, emissiveStrength included
    float roughness = 1.0f;  // perceptual; GGX alpha = roughness^2
    // Dielectric reflectance at normal incidence: ((ior - 1) / (ior + 1))^2 times
    // KHR_materials_specular's colour factor, kept at most 1 after its texture is applied;
    // specularWeight is its specularFactor.
    vec3 dielectricF0{0.04f};
    float specularWeight = 1.0f;
    uint32_t metallicRoughnessTexture = kNoTexture;  // roughness in green, metalness in blue
    uint32_t normalTexture = kNoTexture;             // tangent space, +y towards -v
    uint32_t emissiveTexture = kNoTexture;
    uint32_t occlusionTexture = kNoTexture;  // red; darkens ambient light only
    float normalScale = 1.0f;
    float occlusionStrength = 1.0f;
    float transmission = 0.0f;  // KHR_materials_transmission: the dielectric's diffuse share
    float ior = 1.5f;
    vec3 ambientLight{0.1f};  // the uniform light around the object that stands for indirect light
    uint32_t transmissionTexture = kNoTexture;  // red, times transmission
    // KHR_materials_specular's textures: the strength (the image's alpha, recorded as grey)
    // times specularWeight, and the colour (sRGB) times dielectricF0.
    uint32_t specularTexture = kNoTexture;
    uint32_t specularColorTexture = kNoTexture;
    // 1 without KHR_materials_volume (or with thickness 0): a thin wall, which what it transmits
    // passes through unbent; 0: the surface of a refracting volume.
    uint32_t thinWalled = 0;
    uint32_t pad = 0;
};
static_assert(sizeof(PbrMaterial) == 112);

}  // namespace rtrt
