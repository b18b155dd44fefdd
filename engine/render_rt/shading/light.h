#pragma once
// Punctual lights: directional, point and spot, each casting hard shadows. A light's colour is the
// radiance a white Lambertian surface facing it shows, illuminance / pi: Blinn-Phong's diffuse
// term multiplies it as it is, the PBR BRDF takes pi times it as illuminance. rtrt's own lights
// keep their colour at every distance unless they opt in to inverse-square falloff; glTF's
// KHR_lights_punctual lights always fall off, their physical units (lux for directional lights,
// candela for point and spot lights) divided by pi.
#include "engine/core/math.h"

namespace rtrt {

enum class LightType : uint32_t { kDirectional = 0, kPoint = 1, kSpot = 2 };

// 64 bytes. vector is the unit direction toward a directional light, else the light's position.
// A spot light's cone weight is clamp(cos(angle to its axis) * spotScale + spotOffset, 0, 1)^2
// (KHR_lights_punctual's smooth cone between its inner and outer angles).
struct Light {
    vec3 vector{1, 1, 1};
    LightType type = LightType::kDirectional;
    vec3 color{1.0f};
    float range = 0.0f;       // with falloff: where the light ends smoothly; 0 = nowhere
    vec3 spotAxis{0, 0, -1};  // unit direction a spot light shines along
    uint32_t falloff = 0;     // 1: intensity / distance^2 (point and spot lights)
    float spotScale = 0.0f, spotOffset = 1.0f;
    float pad[2] = {};
};
static_assert(sizeof(Light) == 64);

// The spot cone's scale and offset from its inner and outer angles (radians), as the
// KHR_lights_punctual specification computes them.
inline void SetSpotCone(Light* light, float innerAngle, float outerAngle) {
    const float cosOuter = cosf(outerAngle);
    light->spotScale = 1.0f / fmaxf(1e-3f, cosf(innerAngle) - cosOuter);
    light->spotOffset = -cosOuter * light->spotScale;
}

// What reaches a point of the light's colour: 1/d^2 windowed smoothly to 0 at range
// (KHR_lights_punctual's recommended window, clamp(1 - (d/range)^4, 0, 1)^2) for lights with
// falloff, times the spot cone. toLight runs from the point to a point or spot light
// (unnormalised), l is its unit direction.
RT_HD inline float LightAttenuation(const Light& light, vec3 toLight, vec3 l) {
    float attenuation = 1.0f;
    if (light.falloff != 0) {
        const float d2 = glm::dot(toLight, toLight);
        attenuation = 1.0f / fmaxf(d2, 1e-12f);
        if (light.range > 0.0f) {
            const float ratio2 = d2 / (light.range * light.range);
            const float window = fminf(fmaxf(1.0f - ratio2 * ratio2, 0.0f), 1.0f);
            attenuation *= window * window;
        }
    }
    if (light.type == LightType::kSpot) {
        const float cone = fminf(
            fmaxf(-glm::dot(l, light.spotAxis) * light.spotScale + light.spotOffset, 0.0f), 1.0f);
        attenuation *= cone * cone;
    }
    return attenuation;
}

// Whether LightAttenuation can differ from 1: rtrt's own lights without falloff skip it, so their
// images stay bit for bit what they were.
RT_HD inline bool LightAttenuates(const Light& light) {
    return light.falloff != 0 || light.type == LightType::kSpot;
}

}  // namespace rtrt
