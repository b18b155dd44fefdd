#pragma once
// The sRGB transfer function (IEC 61966-2-1): 8-bit images and textures store sRGB-encoded
// values; shading and blending happen in linear light.
#include "engine/core/math.h"
#include "engine/core/rt_hd.h"

namespace rtrt {

// Linear 0..1 to the encoded value (outside: clamped; NaN: 0).
RT_HD inline float SrgbEncode(float linear) {
    if (!(linear > 0.0f)) return 0.0f;
    if (linear >= 1.0f) return 1.0f;
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * powf(linear, 1.0f / 2.4f) - 0.055f;
}

// The encoded value 0..1 back to linear.
RT_HD inline float SrgbDecode(float encoded) {
    if (!(encoded > 0.0f)) return 0.0f;
    if (encoded >= 1.0f) return 1.0f;
    return encoded <= 0.04045f ? encoded / 12.92f : powf((encoded + 0.055f) / 1.055f, 2.4f);
}

}  // namespace rtrt
