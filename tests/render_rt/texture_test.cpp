// Texture sampling (texture.h): wrap modes and filters at known coordinates, and sRGB texels
// decoded before they are filtered.
#include "engine/render_rt/texture.h"

#include <gtest/gtest.h>

namespace rtrt {
namespace {

TEST(TextureSampling, WrapModes) {
    // A 4x1 texture of grey levels 0, 1, 2, 3 (x 10), sampled at texel centres beyond [0, 1).
    const uint32_t texels[4] = {0, 10, 20, 30};
    Texture t;
    t.width = 4;
    t.height = 1;
    t.filter = TextureFilter::kNearest;
    auto at = [&](float u, TextureWrap wrap) {
        t.wrapS = wrap;
        return SampleTexture(t, texels, vec2(u, 0.5f)).x * 255.0f;
    };
    EXPECT_FLOAT_EQ(at(1.125f, TextureWrap::kRepeat), 0.0f);
    EXPECT_FLOAT_EQ(at(-0.125f, TextureWrap::kRepeat), 30.0f);
    EXPECT_FLOAT_EQ(at(1.125f, TextureWrap::kMirroredRepeat), 30.0f);
    EXPECT_FLOAT_EQ(at(1.375f, TextureWrap::kMirroredRepeat), 20.0f);
    EXPECT_FLOAT_EQ(at(-0.125f, TextureWrap::kMirroredRepeat), 0.0f);
    EXPECT_FLOAT_EQ(at(7.0f, TextureWrap::kClampToEdge), 30.0f);
    EXPECT_FLOAT_EQ(at(-3.0f, TextureWrap::kClampToEdge), 0.0f);
    EXPECT_FLOAT_EQ(at(1e38f, TextureWrap::kRepeat), at(0.0f, TextureWrap::kRepeat));
    t.filter = TextureFilter::kLinear;
    // Half way between the centres of texels 1 and 2; and across the repeat seam.
    EXPECT_NEAR(at(0.5f, TextureWrap::kRepeat), 15.0f, 1e-4f);
    EXPECT_NEAR(at(0.0f, TextureWrap::kRepeat), 15.0f, 1e-4f);  // texels 3 and 0
    EXPECT_NEAR(at(0.0f, TextureWrap::kClampToEdge), 0.0f, 1e-4f);
}

TEST(TextureSampling, SrgbTexelsAreDecodedBeforeFiltering) {
    // Black and white texels: half way between them the blend of the decoded values is 0.5 in
    // linear light (not the decoded 0.5 of the encoded blend, 0.214).
    const uint32_t texels[2] = {0x000000u, 0xffffffu};
    Texture t;
    t.width = 2;
    t.height = 1;
    t.wrapS = TextureWrap::kClampToEdge;
    t.srgb = 1;
    EXPECT_NEAR(SampleTexture(t, texels, vec2(0.5f, 0.5f)).x, 0.5f, 1e-6f);
    const uint32_t grey[1] = {0x808080u};  // 128: linear 0.2158605
    t.width = 1;
    EXPECT_NEAR(SampleTexture(t, grey, vec2(0.5f, 0.5f)).y, 0.2158605f, 1e-6f);
    t.srgb = 0;
    EXPECT_FLOAT_EQ(SampleTexture(t, grey, vec2(0.5f, 0.5f)).y, 128.0f / 255.0f);
}

}  // namespace
}  // namespace rtrt
