// The textures of KHR_materials_transmission (red, times transmissionFactor) and
// KHR_materials_specular (alpha times specularFactor; sRGB colour times specularColorFactor),
// against materials whose factors alone say the same: a constant texture must render exactly as
// its value in the factor. They had been ignored (a transmissionTexture of 0 left a surface
// fully transmissive).
#include <gtest/gtest.h>

#include <functional>

#include "engine/render_rt/renderer.h"
#include "engine/render_rt/shading/texture.h"
#include "engine/render_rt/srgb.h"
#include "game/scene/scene_file.h"
#include "tests/gltf/gltf_builder.h"
#include "tests/gltf/gltf_test_dir.h"

namespace rtrt {
namespace {

using test::GltfBuilder;
using Json = nlohmann::json;

// Linear radiance of the lit quad (test::LitQuadScene) with its material edited.
Image Render(const GltfBuilder& b, const std::string& path) {
    GltfBuilder::Save(path, b.Glb());
    const LoadedScene loaded = LoadSceneFile(path);
    RenderSettings settings;
    settings.width = settings.height = 8;
    settings.maxDepth = 2;  // the refracted ray and what it meets
    return RenderRaw(loaded.scene, settings);
}

float LargestDifference(const Image& a, const Image& b) {
    float largest = 0.0f;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c)
                largest = std::max(largest, std::fabs(a.At(x, y)[c] - b.At(x, y)[c]));
    return largest;
}

TEST_F(GltfTest, ExtensionTexturesRenderAsTheirValueInTheFactor) {
    struct Case {
        const char* name;
        std::vector<uint8_t> texel;  // RGBA of the 1x1 texture
        std::function<void(Json&)> textured, factorOnly;
        bool textureMatters = true;  // the factors alone render otherwise
    };
    auto ext = [](Json& m, const char* name) -> Json& { return m["extensions"][name]; };
    const Case cases[] = {
        {"transmission texture 0 (its green and blue 255)",
         {0, 255, 255, 255},
         [&](Json& m) {
             ext(m, "KHR_materials_transmission") = {{"transmissionFactor", 1.0},
                                                     {"transmissionTexture", {{"index", 0}}}};
         },
         [&](Json& m) {
             ext(m, "KHR_materials_transmission") = {{"transmissionFactor", 0.0}};
         }},
        {"transmission texture 1 times factor 0.75",
         {255, 0, 0, 0},
         [&](Json& m) {
             ext(m, "KHR_materials_transmission") = {{"transmissionFactor", 0.75},
                                                     {"transmissionTexture", {{"index", 0}}}};
         },
         [&](Json& m) {
             ext(m, "KHR_materials_transmission") = {{"transmissionFactor", 0.75}};
         },
         false},
        {"specular texture alpha 0",
         {255, 255, 255, 0},
         [&](Json& m) {
             ext(m, "KHR_materials_specular") = {{"specularTexture", {{"index", 0}}}};
         },
         [&](Json& m) {
             ext(m, "KHR_materials_specular") = {{"specularFactor", 0.0}};
         }},
        // 128 is 0.216 in linear light: a texture read as linear would give 0.502.
        {"specular colour texture (sRGB)",
         {128, 0, 255, 255},
         [&](Json& m) {
             ext(m, "KHR_materials_specular") = {{"specularColorFactor", {1, 1, 1}},
                                                 {"specularColorTexture", {{"index", 0}}}};
         },
         [&](Json& m) {
             ext(m, "KHR_materials_specular") = {
                 {"specularColorFactor", {SrgbDecode(128.0f * (1.0f / 255.0f)), 0, 1}}};
         }},
    };
    for (const Case& c : cases) {
        GltfBuilder textured = test::LitQuadScene(GltfBuilder::Png(1, 1, c.texel));
        GltfBuilder factorOnly = textured;
        c.textured(textured.doc["materials"][0]);
        c.factorOnly(factorOnly.doc["materials"][0]);
        const Image a = Render(textured, (dir_ / "textured.glb").string());
        const Image b = Render(factorOnly, (dir_ / "factor.glb").string());
        EXPECT_LT(LargestDifference(a, b), 1e-5f) << c.name;
        // And the texture matters: without it the factor alone differs.
        GltfBuilder untextured = textured;
        Json& e = untextured.doc["materials"][0]["extensions"];
        for (auto& [name, value] : e.items())
            for (const char* key :
                 {"transmissionTexture", "specularTexture", "specularColorTexture"})
                value.erase(key);
        if (c.textureMatters)
            EXPECT_GT(LargestDifference(Render(untextured, (dir_ / "u.glb").string()), b), 1e-3f)
                << c.name;
    }
}

// The specular strength is the image's alpha: recorded as grey texels, linear, once per image
// and channel choice beside the colour record of the same image.
TEST_F(GltfTest, SpecularTextureRecordsTheAlphaAsGrey) {
    GltfBuilder b = test::LitQuadScene(GltfBuilder::Png(1, 1, {10, 20, 30, 200}));
    b.doc["materials"][0]["extensions"]["KHR_materials_specular"] = {
        {"specularTexture", {{"index", 0}}}, {"specularColorTexture", {{"index", 0}}}};
    const std::string path = Save("specular.glb", b.Glb());
    const LoadedScene loaded = LoadSceneFile(path);
    const PbrMaterial& p = loaded.scene.pbrMaterials.at(0);
    ASSERT_NE(p.specularTexture, kNoTexture);
    ASSERT_NE(p.specularColorTexture, kNoTexture);
    const Texture& strength = loaded.scene.textures[p.specularTexture];
    const Texture& colour = loaded.scene.textures[p.specularColorTexture];
    EXPECT_EQ(strength.srgb, 0u);
    EXPECT_EQ(colour.srgb, 1u);
    EXPECT_EQ(loaded.scene.texels[strength.texelOffset] & 0xffffffu, 200u * 0x010101u);
    EXPECT_EQ(loaded.scene.texels[colour.texelOffset] & 0xffffffu, 10u | 20u << 8 | 30u << 16);
}

}  // namespace
}  // namespace rtrt
