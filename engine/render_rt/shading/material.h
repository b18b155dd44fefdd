#pragma once
#include "engine/core/math.h"

namespace rtrt {

inline constexpr uint32_t kNoTexture = 0xffffffffu;
inline constexpr uint32_t kNoPbrMaterial = 0xffffffffu;

// Blinn-Phong with mirror reflection and Fresnel-weighted refraction, 64 bytes.
// Radiance leaving a hit: (1 - reflectivity - transmissivity) * local
//                       + (reflectivity + transmissivity * F) * reflected
//                       + transmissivity * (1 - F) * refracted,
// with local = ambient + sum over unshadowed lights of
//              lightColor * (diffuse * max(0, n.l) + specular * max(0, n.h)^shininess)
// and F the exact dielectric Fresnel reflectance for index of refraction ior. A base-colour
// texture (an index into the scene's texture table) multiplies diffuse and ambient by its sample.
struct Material {
    vec3 diffuse{0.8f};
    float shininess = 32.0f;
    vec3 ambient{0.08f};
    float reflectivity = 0.0f;
    vec3 specular{0.0f};
    float transmissivity = 0.0f;
    float ior = 1.5f;
    uint32_t baseColorTexture = kNoTexture;
    // kNoPbrMaterial: Blinn-Phong as above; else an index into the scene's PbrMaterial table, and
    // the hit is shaded by the glTF metallic-roughness BRDF instead (pbr_material.h).
    uint32_t pbrMaterial = kNoPbrMaterial;
    // 1: a thin wall (a glTF transmission without KHR_materials_volume): what is transmitted goes
    // on unbent, with F at the wall's face; 0: the surface of a volume of index ior.
    uint32_t thinWalled = 0;
};
static_assert(sizeof(Material) == 64);

}  // namespace rtrt
