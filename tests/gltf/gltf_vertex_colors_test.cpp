// glTF vertex colours (COLOR_0), checked with small files the tests write: each component type
// the specification allows reaches the BLAS exactly, other types and wrong counts are refused by
// name, colours outside [0, 1] are clamped with a warning; in images, a lit diffuse quad whose
// colours vary linearly across it shows the uncoloured image times the colour at each pixel, and
// the default (Blinn-Phong) material's diffuse and ambient colours are tinted.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.h"
#include "engine/render_rt/renderer.h"
#include "game/scene/scene_file.h"
#include "tests/gltf/gltf_builder.h"
#include "tests/gltf/gltf_test_dir.h"

namespace rtrt {
namespace {

using test::GltfBuilder;
using Json = nlohmann::json;

constexpr int kFloat = 5126, kUByte = 5121, kUShort = 5123;

// The quad of corners (-1, -1), (1, -1), (1, 1), (-1, 1) at z = 0, triangles (0, 1, 2) and
// (0, 2, 3), filling the image of a 90-degree camera at z = 1, lit head-on by a sun. With PBR, a
// white dielectric without a specular layer (diffuse only); else no material (Blinn-Phong).
GltfBuilder LitQuad(bool pbr) {
    GltfBuilder b;
    const int pos = b.Floats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, "VEC3", 3);
    const int idx = b.Accessor(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, kUShort, "SCALAR", 1);
    if (pbr) {
        b.doc["materials"] = Json::array(
            {{{"pbrMetallicRoughness",
               {{"baseColorFactor", {1, 1, 1, 1}},
                {"metallicFactor", 0.0},
                {"roughnessFactor", 1.0}}},
              {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}}}});
    }
    const int mesh = b.Mesh(pos, idx, -1, pbr ? 0 : -1);
    b.doc["cameras"] = Json::array(
        {{{"type", "perspective"},
          {"perspective", {{"yfov", M_PI / 2}, {"aspectRatio", 1.0}, {"znear", 0.01}}}}});
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
        Json::array({{{"type", "directional"}, {"color", {1, 1, 1}}, {"intensity", 2}}});
    b.doc["extensionsUsed"] = Json::array({"KHR_lights_punctual"});
    const int quad = b.Node({{"mesh", mesh}});
    const int camera = b.Node({{"camera", 0}, {"translation", {0, 0, 1}}});
    const int light = b.Node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.doc["scenes"] = Json::array({{{"nodes", {quad, camera, light}}}});
    b.doc["scene"] = 0;
    return b;
}

void SetColors(GltfBuilder& b, int accessor) {
    b.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = accessor;
}

// The triangle BLAS of a one-primitive file.
const Blas& QuadBlas(const LoadedScene& loaded) {
    EXPECT_EQ(loaded.scene.instances.size(), 1u);
    return *loaded.scene.blases.at(loaded.scene.instances.at(0).blasId);
}

// Each slot's corners hold the colours of its source triangle's vertices.
void ExpectCorners(const Blas& blas, const std::vector<vec3>& vertexColors) {
    const uint32_t corners[2][3] = {{0, 1, 2}, {0, 2, 3}};
    ASSERT_EQ(blas.colors.size(), blas.PrimCount());
    for (uint32_t s = 0; s < blas.PrimCount(); ++s)
        for (int k = 0; k < 3; ++k) {
            const vec3 want = vertexColors[corners[blas.primIds[s]][k]];
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(blas.colors[s].rgb[3 * k + c], uint16_t(want[c] * 65535.0f + 0.5f))
                    << "slot " << s << " corner " << k << " channel " << c;
        }
}

// The lit quad with VALUES, normalised integers of TYPE, as its COLOR_0.
template <typename T>
std::string WithIntegerColors(const std::vector<T>& values, int type, const char* vec,
                              size_t components) {
    GltfBuilder b = LitQuad(true);
    const int accessor = b.Accessor(values, type, vec, components);
    b.doc["accessors"][accessor]["normalized"] = true;
    SetColors(b, accessor);
    return b.GltfText();
}

// Each slot's 16-bit channels are SCALE times the file's integers (STRIDE per vertex) of its
// source triangle's corners.
template <typename T>
void ExpectNormalizedIntegers(const std::string& path, const std::vector<T>& values,
                              uint32_t stride, uint32_t scale) {
    const LoadedScene loaded = LoadSceneFile(path);
    const Blas& blas = QuadBlas(loaded);
    ASSERT_EQ(blas.colors.size(), 2u);
    const uint32_t corners[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (uint32_t s = 0; s < 2; ++s)
        for (int k = 0; k < 3; ++k)
            for (uint32_t c = 0; c < 3; ++c)
                EXPECT_EQ(blas.colors[s].rgb[3 * k + int(c)],
                          scale * values[stride * corners[blas.primIds[s]][k] + c])
                    << path << " slot " << s << " corner " << k;
}

TEST_F(GltfTest, VertexColoursOfEveryAllowedTypeReachTheBlas) {
    // Floats, RGBA (alpha is not kept: surfaces are opaque).
    GltfBuilder f = LitQuad(true);
    SetColors(f,
              f.Floats({1, 0, 0, 1, 0, 1, 0, 0.5f, 0, 0, 1, 1, 0.25f, 0.5f, 0.75f, 1}, "VEC4", 4));
    ExpectCorners(QuadBlas(LoadSceneFile(Save("floats.gltf", f.GltfText()))),
                  {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.25f, 0.5f, 0.75f}});
    // Normalised bytes, RGB: each byte b is b / 255, 257 b in 16 bits, exactly.
    const std::vector<uint8_t> bytes = {255, 0, 7, 128, 64, 1, 0, 255, 200, 33, 99, 254};
    ExpectNormalizedIntegers(Save("bytes.gltf", WithIntegerColors(bytes, kUByte, "VEC3", 3)), bytes,
                             3, 257);
    // Normalised shorts, RGBA: exact too.
    const std::vector<uint16_t> words = {65535, 0, 1, 9, 30000, 65534, 2,  3,
                                         4,     5, 6, 7, 8,     9,     10, 11};
    ExpectNormalizedIntegers(Save("shorts.gltf", WithIntegerColors(words, kUShort, "VEC4", 4)),
                             words, 4, 1);
}

TEST_F(GltfTest, VertexColoursOfOtherTypesOrCountsAreRefusedByName) {
    GltfBuilder raw = LitQuad(true);  // bytes, not normalised
    const int a = raw.Accessor(std::vector<uint8_t>(12, 9), kUByte, "VEC3", 3);
    SetColors(raw, a);
    try {
        LoadSceneFile(Save("raw.gltf", raw.GltfText()));
        ADD_FAILURE() << "loaded";
    } catch (const InputError& e) {
        EXPECT_EQ(e.Field(), "accessors[" + std::to_string(a) + "]") << e.what();
        EXPECT_NE(std::string(e.what()).find("normalized"), std::string::npos) << e.what();
    }
    GltfBuilder few = LitQuad(true);
    SetColors(few, few.Floats({1, 1, 1, 1, 1, 1, 1, 1, 1}, "VEC3", 3));
    try {
        LoadSceneFile(Save("few.gltf", few.GltfText()));
        ADD_FAILURE() << "loaded";
    } catch (const InputError& e) {
        EXPECT_EQ(e.Field(), "meshes[0].primitives[0].attributes.COLOR_0") << e.what();
    }
}

TEST_F(GltfTest, VertexColoursOutsideTheUnitRangeAreClampedWithAWarning) {
    GltfBuilder b = LitQuad(true);
    SetColors(b, b.Floats({1.5f, -0.25f, 0.5f, 1, 1, 1, 1, 1, 1, 1, 1, 1}, "VEC3", 3));
    ::testing::internal::CaptureStderr();
    const LoadedScene loaded = LoadSceneFile(Save("bright.gltf", b.GltfText()));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find("meshes[0].primitives[0].attributes.COLOR_0: 2 components outside "
                            "[0, 1]"),
              std::string::npos)
        << warnings;
    ExpectCorners(QuadBlas(loaded), {{1, 0, 0.5f}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}});
}

Image Render16(const LoadedScene& loaded) {
    RenderSettings s;
    s.width = s.height = 16;
    s.maxDepth = 1;
    return RenderRaw(loaded.scene, s);
}

// Colours linear in x are what barycentric interpolation reproduces on either triangle: each
// pixel is the white quad's times ((x + 1) / 2, (1 - x) / 2, 1/4) at its centre's x.
TEST_F(GltfTest, VertexColoursMultiplyTheBaseColourAsInterpolated) {
    GltfBuilder white = LitQuad(true);
    const Image plain = Render16(LoadSceneFile(Save("white.gltf", white.GltfText())));
    GltfBuilder b = LitQuad(true);
    SetColors(b, b.Floats({0, 1, 0.25f, 1, 0, 0.25f, 1, 0, 0.25f, 0, 1, 0.25f}, "VEC3", 3));
    const LoadedScene loaded = LoadSceneFile(Save("ramp.gltf", b.GltfText()));
    const Image coloured = Render16(loaded);
    const float quarter = float(uint16_t(0.25f * 65535.0f + 0.5f)) / 65535.0f;
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x) {
            const float u = (float(x) + 0.5f) / 16.0f;  // (x + 1) / 2 at the pixel centre
            const vec3 tint(u, 1.0f - u, quarter);
            for (int c = 0; c < 3; ++c) {
                const float want = plain.At(x, y)[c] * tint[c];
                ASSERT_GT(plain.At(x, y)[c], 0.01f);
                EXPECT_NEAR(coloured.At(x, y)[c], want, 2e-5f * plain.At(x, y)[c] + 1e-6f)
                    << x << "," << y << " channel " << c;
            }
        }
}

// Blinn-Phong: colours multiply the default material's diffuse and ambient colours (it has no
// highlight): vertices of (1, 0, 1/2) keep red bit for bit, take green out and halve blue.
TEST_F(GltfTest, VertexColoursTintTheDefaultMaterial) {
    GltfBuilder grey = LitQuad(false);
    const Image plain = Render16(LoadSceneFile(Save("grey.gltf", grey.GltfText())));
    GltfBuilder b = LitQuad(false);
    SetColors(b, b.Floats({1, 0, 0.5f, 1, 0, 0.5f, 1, 0, 0.5f, 1, 0, 0.5f}, "VEC3", 3));
    const Image tinted = Render16(LoadSceneFile(Save("tinted.gltf", b.GltfText())));
    const float half = float(uint16_t(0.5f * 65535.0f + 0.5f)) / 65535.0f;
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x) {
            ASSERT_GT(plain.At(x, y).z, 0.01f);
            EXPECT_EQ(tinted.At(x, y).x, plain.At(x, y).x) << x << "," << y;
            EXPECT_EQ(tinted.At(x, y).y, 0.0f) << x << "," << y;
            EXPECT_NEAR(tinted.At(x, y).z, plain.At(x, y).z * half, 1e-6f * plain.At(x, y).z)
                << x << "," << y;
        }
}

}  // namespace
}  // namespace rtrt
