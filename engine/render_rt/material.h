#pragma once
#include "engine/core/math.h"

namespace rtrt {

inline constexpr uint32_t kNoTexture = 0xffffffffu;

// Blinn-Phong with mirror reflection and Fresnel-weighted refraction, 48 bytes.
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
    float pad[2] = {};
};
static_assert(sizeof(Material) == 64);

enum class LightType : uint32_t { kDirectional = 0, kPoint = 1 };

// A directional light (vector = unit direction toward the light) or a point light
// (vector = position); both cast hard shadows.
struct Light {
    vec3 vector{1, 1, 1};
    LightType type = LightType::kDirectional;
    vec3 color{1.0f};
    float pad = 0.0f;
};
static_assert(sizeof(Light) == 32);

}  // namespace rtrt
