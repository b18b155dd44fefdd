// The output transform against its formulas at known values: the sRGB transfer function
// (IEC 61966-2-1), Khronos PBR Neutral, Narkowicz's ACES fit, and the identity that display-value
// scenes take.
#include "engine/render_rt/output_transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rtrt {
namespace {

TEST(SrgbTest, TransferFunctionAtKnownValues) {
    EXPECT_EQ(SrgbEncode(0.0f), 0.0f);
    EXPECT_EQ(SrgbEncode(1.0f), 1.0f);
    // The linear segment and its joint with the curve (both sides give 0.04045 there).
    EXPECT_FLOAT_EQ(SrgbEncode(0.001f), 0.01292f);
    EXPECT_NEAR(SrgbEncode(0.0031308f), 0.04045f, 1e-6f);
    EXPECT_NEAR(1.055f * std::pow(0.0031308f, 1.0f / 2.4f) - 0.055f, 0.04045f, 1e-5f);
    // Mid grey: linear 0.5 is encoded 0.735357, byte 188; 18% grey is 0.461356, byte 118.
    EXPECT_NEAR(SrgbEncode(0.5f), 0.735357f, 1e-5f);
    EXPECT_EQ(DisplayByte(SrgbEncode(0.5f)), 188);
    EXPECT_NEAR(SrgbEncode(0.18f), 0.461356f, 1e-5f);
    EXPECT_EQ(DisplayByte(SrgbEncode(0.18f)), 118);
    EXPECT_NEAR(SrgbDecode(0.5f), 0.214041f, 1e-6f);
    EXPECT_FLOAT_EQ(SrgbDecode(0.04045f), 0.04045f / 12.92f);
    // Out of range and NaN.
    EXPECT_EQ(SrgbEncode(-1.0f), 0.0f);
    EXPECT_EQ(SrgbEncode(7.0f), 1.0f);
    EXPECT_EQ(SrgbEncode(std::numeric_limits<float>::quiet_NaN()), 0.0f);
}

TEST(SrgbTest, EveryByteDecodesAndEncodesBackToItself) {
    for (int b = 0; b < 256; ++b)
        EXPECT_EQ(DisplayByte(SrgbEncode(SrgbDecode(b / 255.0f))), b) << b;
}

TEST(PbrNeutralTest, FormulasAtKnownValues) {
    // Below the start of compression (0.76) only the offset applies: 0.04 above x = 0.08 ...
    const vec3 mid = PbrNeutral(vec3(0.5f, 0.3f, 0.1f));
    EXPECT_FLOAT_EQ(mid.x, 0.46f);
    EXPECT_FLOAT_EQ(mid.y, 0.26f);
    EXPECT_FLOAT_EQ(mid.z, 0.06f);
    // ... and x - 6.25 x^2 below it.
    const vec3 dark = PbrNeutral(vec3(0.02f));
    EXPECT_FLOAT_EQ(dark.x, 0.02f - (0.02f - 6.25f * 0.02f * 0.02f));
    // White at 1: offset to 0.96, compressed to 1 - 0.24^2 / (0.96 + 0.24 - 0.76); grey stays
    // grey under the desaturation.
    const vec3 white = PbrNeutral(vec3(1.0f));
    const float peak = 1.0f - 0.24f * 0.24f / 0.44f;
    EXPECT_NEAR(white.x, peak, 1e-6f);
    EXPECT_NEAR(white.y, peak, 1e-6f);
    EXPECT_NEAR(white.z, peak, 1e-6f);
    // Very bright colours approach white from below.
    const vec3 hot = PbrNeutral(vec3(1e4f, 10.0f, 1.0f));
    EXPECT_LT(hot.x, 1.0f);
    EXPECT_GT(hot.x, 0.9999f);
    EXPECT_GT(hot.z, 0.0f);
}

TEST(PbrNeutralTest, MonotonicAndBelowOne) {
    float previous = -1.0f;
    for (float v = 0.0f; v < 100.0f; v += 0.01f) {
        const float out = PbrNeutral(vec3(v)).x;
        EXPECT_GE(out, previous) << v;
        EXPECT_LT(out, 1.0f) << v;
        previous = out;
    }
}

TEST(AcesTest, FitAtKnownValues) {
    EXPECT_EQ(AcesFit(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(AcesFit(1.0f), 2.54f / 3.16f);
    const vec3 hot = ApplyOutputTransform(vec3(1e6f), {0.0f, ToneMap::kAces, 0});
    EXPECT_EQ(hot.x, 1.0f);  // the fit tends to 2.51 / 2.43 and is clamped
}

// Radiance beyond float's range is white under every tone map, NaN is black, and float files
// store neither: a light of 1e34 under exposure had made lit pixels NaN (inf / inf) and so black.
TEST(OutputTransformTest, OverflowedRadianceIsWhite) {
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (ToneMap map : {ToneMap::kClamp, ToneMap::kPbrNeutral, ToneMap::kAces})
        for (float v : {inf, 3e38f, 1e20f}) {
            const vec3 c = ApplyOutputTransform(vec3(v, 0.0f, v), {20.0f, map, 1});
            EXPECT_EQ(c.x, 1.0f) << ToneMapName(map) << " " << v;
            EXPECT_EQ(c.z, 1.0f) << ToneMapName(map) << " " << v;
            EXPECT_FALSE(std::isnan(c.y)) << ToneMapName(map) << " " << v;
            EXPECT_EQ(ApplyOutputTransform(vec3(nan), {0.0f, map, 1}).x, 0.0f) << ToneMapName(map);
        }
    EXPECT_EQ(FiniteRadiance(inf), std::numeric_limits<float>::max());
    EXPECT_EQ(FiniteRadiance(nan), 0.0f);
    EXPECT_EQ(FiniteRadiance(-2.0f), 0.0f);
    EXPECT_EQ(FiniteRadiance(0.5f), 0.5f);
}

TEST(OutputTransformTest, DisplayValuesAreOnlyClamped) {
    for (float v : {-1.0f, 0.0f, 0.25f, 0.5f, 0.999f, 1.0f, 3.0f})
        EXPECT_EQ(ApplyOutputTransform(vec3(v), kDisplayValues).x,
                  std::fmin(std::fmax(v, 0.f), 1.f));
    EXPECT_EQ(ApplyOutputTransform(vec3(std::numeric_limits<float>::quiet_NaN()), kDisplayValues).x,
              0.0f);
    // The bytes are what rtrt has always written: clamp(v) * 255 rounded.
    for (int i = 0; i <= 1000; ++i) {
        const float v = i / 1000.0f;
        EXPECT_EQ(DisplayByte(ApplyOutputTransform(vec3(v), kDisplayValues).x),
                  uint8_t(v * 255.0f + 0.5f));
    }
}

TEST(OutputTransformTest, ExposureScalesByPowersOfTwo) {
    const OutputTransform plusOne{1.0f, ToneMap::kClamp, 0};
    EXPECT_EQ(ApplyOutputTransform(vec3(0.25f), plusOne).x, 0.5f);
    const OutputTransform minusTwo{-2.0f, ToneMap::kClamp, 1};
    EXPECT_FLOAT_EQ(ApplyOutputTransform(vec3(2.0f), minusTwo).x, SrgbEncode(0.5f));
    // Linear 0.5 through the default pipeline of linear scenes: PBR Neutral's 0.46, then sRGB.
    EXPECT_FLOAT_EQ(ApplyOutputTransform(vec3(0.5f), kLinearToSrgb).x, SrgbEncode(0.46f));
}

TEST(OutputTransformTest, ToneMapNames) {
    ToneMap t = ToneMap::kClamp;
    EXPECT_TRUE(ParseToneMap("aces", &t));
    EXPECT_EQ(t, ToneMap::kAces);
    EXPECT_TRUE(ParseToneMap("pbr_neutral", &t));
    EXPECT_EQ(t, ToneMap::kPbrNeutral);
    EXPECT_FALSE(ParseToneMap("pbr", &t));
    EXPECT_FALSE(ParseToneMap("acesx", &t));
    EXPECT_STREQ(ToneMapName(ToneMap::kAces), "aces");
}

}  // namespace
}  // namespace rtrt
