// Per-vertex colours in 16-bit channels: 8- and 16-bit file colours come back exactly, floats
// within half a step, anything outside [0, 1] (NaN too) clamped; interpolation weights the
// corners by barycentrics.
#include <gtest/gtest.h>

#include "engine/geometry/primitives.h"

namespace rtrt {
namespace {

TEST(TriangleColors, EightAndSixteenBitColoursComeBackExactly) {
    for (uint32_t byte = 0; byte < 256; ++byte) {
        const float v = float(byte) / 255.0f;  // as glTF's normalised bytes are read
        const TriangleColors t = TriangleColors::Pack(vec3(v), vec3(0.0f), vec3(1.0f));
        EXPECT_EQ(t.rgb[0], byte * 257u) << byte;
        EXPECT_FLOAT_EQ(t.Corner(0).x, v) << byte;  // within 4 ulps
    }
    for (uint32_t word : {0u, 1u, 2u, 255u, 256u, 32767u, 32768u, 65534u, 65535u}) {
        const float v = float(word) / 65535.0f;
        EXPECT_EQ(TriangleColors::Pack(vec3(v), vec3(v), vec3(v)).rgb[4], word) << word;
    }
}

TEST(TriangleColors, FloatsRoundToTheNearestStepAndClamp) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const TriangleColors t =
        TriangleColors::Pack(vec3(0.3f, 0.7f, 1e-6f), vec3(-0.5f, 1.5f, nan), vec3(1.0f));
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(t.Corner(0)[k], vec3(0.3f, 0.7f, 1e-6f)[k], 0.5f / 65535.0f) << k;
    EXPECT_EQ(t.Corner(1), vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(t.Corner(2), vec3(1.0f));
}

TEST(TriangleColors, InterpolationWeightsTheCornersByBarycentrics) {
    const TriangleColors t = TriangleColors::Pack(vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1));
    EXPECT_EQ(t.At(0.0f, 0.0f), vec3(1, 0, 0));
    EXPECT_EQ(t.At(1.0f, 0.0f), vec3(0, 1, 0));
    EXPECT_EQ(t.At(0.0f, 1.0f), vec3(0, 0, 1));
    const vec3 centre = t.At(0.25f, 0.5f);
    EXPECT_FLOAT_EQ(centre.x, 0.25f);
    EXPECT_FLOAT_EQ(centre.y, 0.25f);
    EXPECT_FLOAT_EQ(centre.z, 0.5f);
}

}  // namespace
}  // namespace rtrt
