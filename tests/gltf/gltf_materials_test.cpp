// glTF materials and textures, checked against small files the tests write with known answers:
// texels reach the image exactly (nearest and bilinear), factors and extensions become the PBR
// material and its Blinn-Phong approximation, every texture slot gets its record with its
// encoding and KHR_texture_transform.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "engine/core/error.h"
#include "engine/render_rt/renderer.h"
#include "game/gltf/gltf_import.h"
#include "game/scene/scene_file.h"
#include "tests/gltf/gltf_builder.h"
#include "tests/gltf/gltf_test_dir.h"

namespace rtrt {
namespace {

using test::GltfBuilder;
using Json = nlohmann::json;

Image RenderScene8(const LoadedScene& loaded, uint32_t size) {
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.maxDepth = 1;
    return RenderRaw(loaded.scene, settings);
}

// Each pixel of an 8x8 image of a 4x4 texture shows its texel, sRGB-decoded or as it is.
void ExpectTexels(const Image& image, const std::vector<uint8_t>& rgb, bool decoded) {
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c) {
                const uint8_t byte = rgb[3 * size_t((y / 2) * 4 + x / 2) + size_t(c)];
                const float v = float(byte) * (1.0f / 255.0f);  // as the sampler computes it
                EXPECT_FLOAT_EQ(image.At(x, y)[c], decoded ? SrgbDecode(v) : v)
                    << x << "," << y << " channel " << c;
            }
}

TEST_F(GltfTest, NearestTexturedQuadShowsItsTexels) {
    std::vector<uint8_t> rgb;
    for (int i = 0; i < 16; ++i)
        rgb.insert(rgb.end(), {uint8_t(16 * i), uint8_t(255 - 9 * i), uint8_t(7 * i + 3)});
    const std::string path = Save("quad.gltf", test::TexturedQuadGltf(4, 4, rgb, 9728, 33071));
    const LoadedScene loaded = LoadSceneFile(path);
    EXPECT_NE(loaded.scene.Features() & kFeatureTextures, 0u);
    ASSERT_EQ(loaded.scene.textures.size(), 1u);
    EXPECT_TRUE(loaded.width == 1280u && loaded.height == 1280u);
    EXPECT_EQ(loaded.output.srgbEncode, 1u);  // a glTF file alone has linear colours
    ExpectTexels(RenderScene8(loaded, 8), rgb, true);
    // In a scene file of display colours the texels are used as they are, as they always were.
    std::ofstream(dir_ / "display.json") << R"({"models": {"q": {"type": "gltf", "file":
        "quad.gltf"}}, "instances": [{"model": "q"}]})";
    ExpectTexels(RenderScene8(LoadSceneFile((dir_ / "display.json").string()), 8), rgb, false);
}

TEST_F(GltfTest, BilinearTexturedQuadBlendsNeighbours) {
    // Two texels, black and white, clamped: along x the colour ramps from the first texel
    // centre (u = 1/4) to the second (u = 3/4) and is flat outside.
    const std::vector<uint8_t> rgb = {0, 0, 0, 255, 255, 255};
    const std::string path = Save("ramp.gltf", test::TexturedQuadGltf(2, 1, rgb, 9729, 33071));
    const Image image = RenderScene8(LoadSceneFile(path), 8);
    for (uint32_t x = 0; x < 8; ++x) {
        const float u = (float(x) + 0.5f) / 8.0f;
        const float expected = std::clamp(2.0f * u - 0.5f, 0.0f, 1.0f);
        EXPECT_NEAR(image.At(x, 3).x, expected, 2e-6f) << x;
    }
}

TEST_F(GltfTest, MaterialMapping) {
    GltfBuilder b = test::TwoLevels();
    b.doc["materials"] =
        Json::array({{{"pbrMetallicRoughness",
                       {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}},
                        {"metallicFactor", 0.0},
                        {"roughnessFactor", 0.5}}},
                      {"emissiveFactor", {0.1, 0.2, 0.3}},
                      {"extensions",
                       {{"KHR_materials_transmission", {{"transmissionFactor", 0.5}}},
                        {"KHR_materials_ior", {{"ior", 1.33}}},
                        {"KHR_materials_emissive_strength", {{"emissiveStrength", 2.0}}}}}}});
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    const LoadedScene loaded = LoadSceneFile(Save("material.gltf", b.GltfText()));
    const Material& m = loaded.scene.materials[0];
    EXPECT_NEAR(glm::length(m.diffuse - vec3(0.25f, 0.125f, 0.5f)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(m.ambient - (vec3(0.05f, 0.025f, 0.1f) + vec3(0.2f, 0.4f, 0.6f))), 0.0f,
                1e-6f);
    EXPECT_FLOAT_EQ(m.transmissivity, 0.5f);
    EXPECT_FLOAT_EQ(m.ior, 1.33f);
    const float f0 = (0.33f / 2.33f) * (0.33f / 2.33f);
    EXPECT_NEAR(m.specular.x, f0, 1e-6f);
    EXPECT_NEAR(m.reflectivity, f0 * 0.25f, 1e-6f);
    // alpha = 0.25: n = 2 / 0.0625 - 2 = 30.
    EXPECT_NEAR(m.shininess, 30.0f, 1e-3f);
    EXPECT_EQ(m.baseColorTexture, kNoTexture);
    // The PBR material itself, which PBR kernels shade (the above is their fallback).
    ASSERT_NE(m.pbrMaterial, kNoPbrMaterial);
    const PbrMaterial& p = loaded.scene.pbrMaterials[m.pbrMaterial];
    EXPECT_EQ(p.baseColor, vec3(0.5f, 0.25f, 1.0f));
    EXPECT_EQ(p.metallic, 0.0f);
    EXPECT_EQ(p.roughness, 0.5f);
    EXPECT_NEAR(glm::length(p.emissive - vec3(0.2f, 0.4f, 0.6f)), 0.0f, 1e-6f);
    EXPECT_NEAR(p.dielectricF0.x, f0, 1e-6f);
    EXPECT_EQ(p.transmission, 0.5f);
    EXPECT_FLOAT_EQ(p.ior, 1.33f);
    const uint32_t features = loaded.scene.Features();
    EXPECT_NE(features & kFeaturePbr, 0u);
    EXPECT_NE(features & kFeatureRefraction, 0u);
}

// KHR_materials_ior takes any index from 1 (a diamond's 2.42, a metal-like 20) and 0, the
// specular-glossiness mode: an infinite index, reflectance 1 at every angle (times
// KHR_materials_specular), nothing transmitted; between 0 and 1 it is refused.
TEST_F(GltfTest, IorBeyondGlassAndItsZeroMode) {
    auto load = [&](double ior) {
        GltfBuilder b = test::TwoLevels();
        b.doc["materials"] = Json::array(
            {{{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
              {"extensions",
               {{"KHR_materials_transmission", {{"transmissionFactor", 0.5}}},
                {"KHR_materials_ior", {{"ior", ior}}},
                {"KHR_materials_specular", {{"specularColorFactor", {0.5, 1.0, 1.0}}}}}}}});
        b.doc["meshes"][0]["primitives"][0]["material"] = 0;
        return LoadSceneFile(Save("ior.gltf", b.GltfText()));
    };
    const LoadedScene twenty = load(20.0);
    const PbrMaterial& p20 = twenty.scene.pbrMaterials[twenty.scene.materials[0].pbrMaterial];
    EXPECT_FLOAT_EQ(p20.ior, 20.0f);
    EXPECT_FLOAT_EQ(p20.dielectricF0.y, (19.0f / 21.0f) * (19.0f / 21.0f));
    EXPECT_EQ(p20.transmission, 0.5f);

    const LoadedScene zero = load(0.0);
    const Material& m0 = zero.scene.materials[0];
    const PbrMaterial& p0 = zero.scene.pbrMaterials[m0.pbrMaterial];
    EXPECT_EQ(p0.dielectricF0, vec3(0.5f, 1.0f, 1.0f));
    EXPECT_EQ(p0.transmission, 0.0f);
    EXPECT_EQ(m0.transmissivity, 0.0f);
    EXPECT_GE(p0.ior, 1e6f);
    EXPECT_EQ(zero.scene.Features() & kFeatureRefraction, 0u);

    for (const double bad : {0.5, -1.0}) {
        try {
            load(bad);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(
                          "materials[0].extensions.KHR_materials_ior.ior: must be 0 or at least 1"),
                      std::string::npos)
                << e.what();
        }
    }
}

// The textured quad (nearest, clamped) with a 4 x 4 grey BMP as its image, in a data URI.
GltfBuilder GreyBmpQuad() {
    GltfBuilder b = test::TexturedQuadScene(9728, 33071);
    const std::vector<uint8_t> rgb(16 * 3, 200);
    const std::string bmp = GltfBuilder::Bmp(4, 4, rgb);
    b.doc["images"] =
        Json::array({{{"uri", "data:image/bmp;base64," + GltfBuilder::Base64(std::vector<uint8_t>(
                                                             bmp.begin(), bmp.end()))}}});
    return b;
}

// Every texture slot of a material, KHR_texture_transform on two of them: one image decoded once
// per encoding, recorded once per encoding and transform, the transform as the specification's
// matrix.
TEST_F(GltfTest, PbrTextureSlotsAndTransforms) {
    GltfBuilder b = GreyBmpQuad();
    Json& m = b.doc["materials"][0];
    const Json transform = {
        {"KHR_texture_transform", {{"offset", {0.5, 0.25}}, {"rotation", 0.0}, {"scale", {2, 3}}}}};
    m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", 0},
                                                             {"extensions", transform}};
    m["normalTexture"] = {{"index", 0}, {"scale", 0.5}, {"extensions", transform}};
    m["occlusionTexture"] = {{"index", 0}, {"strength", 0.25}};
    b.doc["extensionsUsed"] = Json::array({"KHR_lights_punctual", "KHR_texture_transform"});
    const LoadedScene loaded = LoadSceneFile(Save("slots.gltf", b.GltfText()));
    const Material& mat = loaded.scene.materials[0];
    const PbrMaterial& p = loaded.scene.pbrMaterials[mat.pbrMaterial];
    const auto& textures = loaded.scene.textures;
    // Base colour and emissive (sRGB, untransformed) share a record; occlusion (linear,
    // untransformed) has its own; metallic-roughness and normal (linear, transformed) share one.
    EXPECT_EQ(mat.baseColorTexture, p.emissiveTexture);
    EXPECT_EQ(p.metallicRoughnessTexture, p.normalTexture);
    EXPECT_EQ(textures.size(), 3u);
    // The image once per encoding (its sampler asks for no mip levels).
    EXPECT_EQ(loaded.scene.texels.size(), 32u);
    EXPECT_EQ(textures[mat.baseColorTexture].srgb, 1u);
    EXPECT_EQ(textures[p.occlusionTexture].srgb, 0u);
    EXPECT_EQ(textures[p.occlusionTexture].transformed, 0u);
    const Texture& t = textures[p.normalTexture];
    EXPECT_EQ(t.srgb, 0u);
    ASSERT_EQ(t.transformed, 1u);
    const float expected[6] = {2, 0, 0.5f, 0, 3, 0.25f};
    for (int i = 0; i < 6; ++i) EXPECT_FLOAT_EQ(t.uvTransform[i], expected[i]) << i;
    EXPECT_EQ(p.normalScale, 0.5f);
    EXPECT_EQ(p.occlusionStrength, 0.25f);
}

// Textures that name one image share its texels: 64 textures of one 4096^2 image had built 64
// mip chains (out of memory from a 57 KB file). Textures of other samplers keep their own
// records.
TEST_F(GltfTest, TexturesOfOneImageShareItsTexels) {
    GltfBuilder b = GreyBmpQuad();
    b.doc["samplers"].push_back({{"magFilter", 9729}, {"minFilter", 9729}, {"wrapS", 10497}});
    b.doc["textures"] = Json::array({{{"source", 0}, {"sampler", 0}},
                                     {{"source", 0}, {"sampler", 1}},
                                     {{"source", 0}, {"sampler", 0}}});
    Json& m = b.doc["materials"][0];
    m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    m["emissiveTexture"] = {{"index", 1}};
    m["occlusionTexture"] = {{"index", 2}};
    const LoadedScene loaded = LoadSceneFile(Save("shared.gltf", b.GltfText()));
    const PbrMaterial& p = loaded.scene.pbrMaterials[loaded.scene.materials[0].pbrMaterial];
    const auto& textures = loaded.scene.textures;
    // sRGB once (base colour, emissive) and linear once (occlusion): 16 texels each, the
    // samplers ask for no mip levels.
    EXPECT_EQ(loaded.scene.texels.size(), 32u);
    const Texture& base = textures[loaded.scene.materials[0].baseColorTexture];
    const Texture& emissive = textures[p.emissiveTexture];
    EXPECT_EQ(base.texelOffset, emissive.texelOffset);
    EXPECT_NE(base.wrapS, emissive.wrapS);  // each its own sampler
    EXPECT_NE(textures[p.occlusionTexture].texelOffset, base.texelOffset);
}

// A glTF shown alone is exposed for its key light: a 2,000 lux sun makes a white surface show 1
// before tone mapping; a lamp at the very centre of the scene counts from a quarter of the
// scene's radius, not from 0.
// A normal-mapped primitive's BLAS keeps vertex tangents: the file's TANGENT (normalised, w
// reduced to its sign) where it has one, else generated along increasing u; a primitive without
// a normal map keeps none.
TEST_F(GltfTest, NormalMappedPrimitivesGetVertexTangents) {
    const std::vector<uint8_t> rgb(16 * 3, 128);
    const std::string bmp = GltfBuilder::Bmp(4, 4, rgb);
    auto scene = [&](bool normalMap, bool tangents) {
        GltfBuilder b = test::TexturedQuadScene(9729, 10497);
        b.doc["images"] = Json::array(
            {{{"uri", "data:image/bmp;base64," +
                          GltfBuilder::Base64(std::vector<uint8_t>(bmp.begin(), bmp.end()))}}});
        if (normalMap) b.doc["materials"][0]["normalTexture"] = {{"index", 0}};
        if (tangents)
            b.doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] =
                b.Floats({0, 2, 0, 1, 0, 2, 0, 1, 0, 2, 0, -0.5f, 0, 2, 0, -1}, "VEC4", 4);
        return LoadSceneFile(Save("quad.gltf", b.GltfText()));
    };
    const LoadedScene plain = scene(false, true);
    EXPECT_TRUE(plain.scene.blases[0]->tangents.empty());
    const LoadedScene given = scene(true, true);
    ASSERT_EQ(given.scene.blases[0]->tangents.size(), 2u);
    const std::vector<uint32_t>& ids = given.scene.blases[0]->primIds;
    for (size_t slot = 0; slot < 2; ++slot) {
        const TriangleTangents& t = given.scene.blases[0]->tangents[slot];
        // Triangle 0 is vertices 0, 1, 2 (w 1, 1, -1); triangle 1 is 0, 2, 3 (w 1, -1, -1).
        EXPECT_EQ(t.t0, vec4(0, 1, 0, 1));
        EXPECT_EQ(t.t1, ids[slot] == 0 ? vec4(0, 1, 0, 1) : vec4(0, 1, 0, -1));
        EXPECT_EQ(t.t2, vec4(0, 1, 0, -1));
    }
    const LoadedScene generated = scene(true, false);
    ASSERT_EQ(generated.scene.blases[0]->tangents.size(), 2u);
    for (const TriangleTangents& t : generated.scene.blases[0]->tangents)
        for (const vec4& v : {t.t0, t.t1, t.t2}) {
            EXPECT_NEAR(v.x, 1.0f, 1e-6f);
            EXPECT_NEAR(v.y, 0.0f, 1e-6f);
            EXPECT_NEAR(v.z, 0.0f, 1e-6f);
            EXPECT_EQ(v.w, 1.0f);  // n x t = +y, up the image: decreasing v
        }
    // A sparse TANGENT accessor (not read by rtrt) is warned about and the tangents generated;
    // it used to escape every handler and abort the process.
    GltfBuilder b = test::TexturedQuadScene(9729, 10497);
    b.doc["images"] =
        Json::array({{{"uri", "data:image/bmp;base64," + GltfBuilder::Base64(std::vector<uint8_t>(
                                                             bmp.begin(), bmp.end()))}}});
    b.doc["materials"][0]["normalTexture"] = {{"index", 0}};
    const int tangent = b.Floats({0, 2, 0, 1, 0, 2, 0, 1, 0, 2, 0, 1, 0, 2, 0, 1}, "VEC4", 4);
    b.doc["accessors"][tangent]["sparse"] = {
        {"count", 1},
        {"indices", {{"bufferView", b.doc["accessors"][0]["bufferView"]}, {"componentType", 5125}}},
        {"values", {{"bufferView", b.doc["accessors"][0]["bufferView"]}}}};
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = tangent;
    ::testing::internal::CaptureStderr();
    const LoadedScene sparse = LoadSceneFile(Save("sparse_tangent.gltf", b.GltfText()));
    const std::string warning = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warning.find("TANGENT: sparse accessors are not supported; the primitive's tangents "
                           "are generated instead"),
              std::string::npos)
        << warning;
    ASSERT_EQ(sparse.scene.blases[0]->tangents.size(), 2u);
    EXPECT_NEAR(sparse.scene.blases[0]->tangents[0].t0.x, 1.0f, 1e-6f);
}

TEST_F(GltfTest, ExposureFollowsTheKeyLight) {
    auto exposure = [&](const Json& light, const Json& at) {
        GltfBuilder b = test::TwoLevels();
        b.doc["extensions"]["KHR_lights_punctual"]["lights"] = Json::array({light});
        b.doc["scenes"][0]["nodes"].push_back(b.Node(
            {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"translation", at}}));
        return LoadSceneFile(Save("lit.gltf", b.GltfText())).output.exposureEv;
    };
    EXPECT_NEAR(exposure({{"type", "directional"}, {"intensity", 2000}}, {0, 0, 0}),
                -std::log2(2000.0 / M_PI), 1e-4);
    const float centred = exposure({{"type", "point"}, {"intensity", 100}}, {2, 0, -1});
    EXPECT_TRUE(std::isfinite(centred));
    EXPECT_GT(centred, -20.0f);
    // A spot 10 above the scene whose cone misses it still sets the exposure where it shines:
    // 100 cd / pi at a distance of 9 to 11.
    const float spot = exposure(
        {{"type", "spot"}, {"intensity", 100}, {"spot", {{"outerConeAngle", 0.2}}}}, {2, 10, -1});
    EXPECT_GT(spot, -std::log2(100.0 / M_PI / 81.0));
    EXPECT_LT(spot, -std::log2(100.0 / M_PI / 121.0));
}

}  // namespace
}  // namespace rtrt
