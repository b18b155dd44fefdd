// Texture sampling (texture.h): wrap modes and filters at known coordinates, sRGB texels decoded
// before they are filtered, mip levels as box filters (in linear light for sRGB), and trilinear
// filtering at a known footprint.
#include "engine/render_rt/shading/texture.h"

#include <gtest/gtest.h>

#include "engine/render_rt/shading/texture_mips.h"

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

TEST(TextureMips, LevelsAreBoxFiltersInLinearLight) {
    // 4 x 2 grey texels 0, 40, 80, 120 / 160, 200, 240, 255: level 1 is 2 x 1, level 2 1 x 1.
    const uint32_t grey[8] = {0, 40, 80, 120, 160, 200, 240, 255};
    uint32_t rgba[8];
    for (int i = 0; i < 8; ++i) rgba[i] = grey[i] * 0x010101u | 0xff000000u;
    ASSERT_EQ(FullMipLevels(4, 2), 3u);
    EXPECT_EQ(TexelCount(4, 2, 3), 8u + 2u + 1u);
    const std::vector<uint32_t> linear = BuildMipChain(rgba, 4, 2, 3, false);
    ASSERT_EQ(linear.size(), 11u);
    EXPECT_EQ(linear[8] & 0xffu, 100u);   // (0 + 40 + 160 + 200) / 4
    EXPECT_EQ(linear[9] & 0xffu, 174u);   // (80 + 120 + 240 + 255) / 4 = 173.75
    EXPECT_EQ(linear[10] & 0xffu, 137u);  // (100 + 174) / 2
    EXPECT_EQ(linear[8] >> 24, 255u);     // alpha averaged too
    // sRGB: black and white average to linear 0.5, byte 188 (not 128).
    const uint32_t bw[2] = {0xff000000u, 0xffffffffu};
    const std::vector<uint32_t> srgb = BuildMipChain(bw, 2, 1, 2, true);
    EXPECT_EQ(srgb[2] & 0xffu, 188u);
    // An odd size folds its last column into the last texel: 3 x 1 -> 1 x 1, all three averaged.
    const uint32_t three[3] = {0, 30, 90};
    EXPECT_EQ(BuildMipChain(three, 3, 1, 2, false)[3], 40u);
}

TEST(TextureMips, TrilinearSamplingAtAKnownFootprint) {
    // An 8 x 8 checkerboard of single black and white texels with its 4 levels: at a footprint
    // of 4 texels (lod 2) every sample is the grey of level 2, exactly; at lod 0 the texels show;
    // half way between levels 0 and 1 the blend is half of each.
    std::vector<uint32_t> checker(64);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) checker[size_t(y * 8 + x)] = (x + y) % 2 ? 0xffffffu : 0u;
    Texture t;
    t.width = t.height = 8;
    t.filter = TextureFilter::kNearest;
    t.levels = FullMipLevels(8, 8);
    ASSERT_EQ(t.levels, 4u);
    const std::vector<uint32_t> chain = BuildMipChain(checker.data(), 8, 8, t.levels, false);
    const float lod0 = -3.0f;                // log2 of one texel in texture coordinates: 1/8
    const float grey = float(128) / 255.0f;  // 127.5 rounds to 128
    for (float u : {0.0625f, 0.3f, 0.77f}) {
        EXPECT_FLOAT_EQ(SampleTexture(t, chain.data(), vec2(u, 0.4f), lod0 + 2.0f).x, grey);
        EXPECT_FLOAT_EQ(SampleTexture(t, chain.data(), vec2(u, 0.4f), lod0).x,
                        SampleTexture(t, chain.data(), vec2(u, 0.4f)).x);
    }
    const float texel = SampleTexture(t, chain.data(), vec2(0.0625f, 0.0625f), lod0).x;  // black
    EXPECT_FLOAT_EQ(texel, 0.0f);
    EXPECT_NEAR(SampleTexture(t, chain.data(), vec2(0.0625f, 0.0625f), lod0 + 0.5f).x, 0.5f * grey,
                1e-6f);
    // A footprint as big as the texture samples the last level, the mean.
    EXPECT_FLOAT_EQ(SampleTexture(t, chain.data(), vec2(0.5f, 0.5f), 5.0f).x, grey);
}

TEST(TextureMips, FootprintOfARayConeOnATriangle) {
    // A unit right triangle with uvs equal to its positions, seen head on by a cone 0.25 wide:
    // log2(0.25); at 60 degrees from the normal the footprint doubles.
    const TriangleUvs uvs{{0, 0}, {1, 0}, {0, 1}};
    const vec3 e1(1, 0, 0), e2(0, 1, 0);
    EXPECT_FLOAT_EQ(TextureFootprint(uvs, e1, e2, 0.25f, 1.0f), -2.0f);
    EXPECT_NEAR(TextureFootprint(uvs, e1, e2, 0.25f, 0.5f), -1.0f, 1e-6f);
    // World edges twice as long: the same uvs cover four times the area, half the footprint.
    EXPECT_NEAR(TextureFootprint(uvs, 2.0f * e1, 2.0f * e2, 0.25f, 1.0f), -3.0f, 1e-6f);
}

}  // namespace
}  // namespace rtrt
