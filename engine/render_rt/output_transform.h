#pragma once
// The output transform at the end of every frame: scene-referred linear radiance to what a
// display or an 8-bit file holds. Exposure (a scale of 2^EV), a tone mapper, then the sRGB
// transfer function. Float outputs (EXR, PFM) skip it and keep the linear values. Scenes whose
// colours are display values already (rtrt's own scene files unless they say "colours":
// "linear") take kDisplayValues, which clamps and nothing else.
#include <cstdint>

#include "engine/core/math.h"
#include "engine/core/rt_hd.h"
#include "engine/render_rt/srgb.h"

namespace rtrt {

enum class ToneMap : uint32_t {
    kClamp = 0,       // values above 1 clip
    kPbrNeutral = 1,  // Khronos PBR Neutral: base colours under light of 1 stay as authored
    kAces = 2,        // Narkowicz 2015's fit of the ACES filmic curve
};

struct OutputTransform {
    float exposureEv = 0.0f;
    ToneMap toneMap = ToneMap::kClamp;
    uint32_t srgbEncode = 0;  // 1: the sRGB transfer function after tone mapping
};
static_assert(sizeof(OutputTransform) == 12);

// Colours that are already display values: clamped, nothing else (what rtrt always did).
inline constexpr OutputTransform kDisplayValues{};
// Linear colours: exposure, PBR Neutral and sRGB encoding.
inline constexpr OutputTransform kLinearToSrgb{0.0f, ToneMap::kPbrNeutral, 1};

// Khronos PBR Neutral tone mapping (the specification's reference formulas): colours below
// 0.76 pass through, after a small offset that keeps darks from washing out; brighter ones are
// compressed toward 1 and desaturated toward white as they pass it.
RT_HD inline vec3 PbrNeutral(vec3 c) {
    constexpr float kStartCompression = 0.8f - 0.04f;
    constexpr float kDesaturation = 0.15f;
    const float x = fminf(c.x, fminf(c.y, c.z));
    const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
    c -= vec3(offset);
    const float peak = fmaxf(c.x, fmaxf(c.y, c.z));
    if (peak < kStartCompression) return c;
    constexpr float d = 1.0f - kStartCompression;
    const float newPeak = 1.0f - d * d / (peak + d - kStartCompression);
    c *= newPeak / peak;
    const float g = 1.0f - 1.0f / (kDesaturation * (peak - newPeak) + 1.0f);
    return c * (1.0f - g) + vec3(newPeak * g);
}

// Narkowicz, "ACES Filmic Tone Mapping Curve" (2015): a rational fit of the ACES reference
// rendering and output transforms, per channel.
RT_HD inline float AcesFit(float x) {
    // Past 1e18 the fit is its limit to float's precision, and x * x would overflow (inf / inf).
    x = fminf(fmaxf(x, 0.0f), 1e18f);
    return (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
}

RT_HD inline float Saturate(float v) { return fminf(fmaxf(v, 0.0f), 1.0f); }

// Radiance as an image stores it: NaN is 0 and what overflowed float is its largest value, so
// that light beyond float's range (a colour of 1e34 under exposure, two lights of 3e38) is white
// after tone mapping, where inf / inf in the tone maps had made it NaN and so black.
RT_HD inline float FiniteRadiance(float v) { return fminf(fmaxf(v, 0.0f), 3.40282347e38f); }
RT_HD inline vec3 FiniteRadiance(vec3 c) {
    return vec3(FiniteRadiance(c.x), FiniteRadiance(c.y), FiniteRadiance(c.z));
}

// Linear radiance to a display value in [0, 1].
RT_HD inline vec3 ApplyOutputTransform(vec3 c, const OutputTransform& t) {
    if (t.exposureEv != 0.0f) c *= exp2f(t.exposureEv);  // display values pass exactly
    c = FiniteRadiance(c);
    if (t.toneMap == ToneMap::kPbrNeutral) c = PbrNeutral(c);
    if (t.toneMap == ToneMap::kAces) c = vec3(AcesFit(c.x), AcesFit(c.y), AcesFit(c.z));
    c = vec3(Saturate(c.x), Saturate(c.y), Saturate(c.z));
    if (t.srgbEncode) c = vec3(SrgbEncode(c.x), SrgbEncode(c.y), SrgbEncode(c.z));
    return c;
}

// The byte an 8-bit output stores for a display value: round(v * 255).
RT_HD inline uint8_t DisplayByte(float v) { return uint8_t(Saturate(v) * 255.0f + 0.5f); }

// "clamp", "pbr_neutral", "aces": false for another name.
inline bool ParseToneMap(const char* name, ToneMap* out) {
    const char* names[] = {"clamp", "pbr_neutral", "aces"};
    for (uint32_t i = 0; i < 3; ++i) {
        const char *a = name, *b = names[i];
        while (*a && *a == *b) ++a, ++b;
        if (*a == *b) {
            *out = ToneMap(i);
            return true;
        }
    }
    return false;
}
inline const char* ToneMapName(ToneMap t) {
    return t == ToneMap::kPbrNeutral ? "pbr_neutral" : t == ToneMap::kAces ? "aces" : "clamp";
}

}  // namespace rtrt
