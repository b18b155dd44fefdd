// glTF files that the specification allows and rtrt had read wrongly: uris with '+' (a plus in
// RFC 3986, a space to tinygltf's form decoding), telephoto cameras under a degree, transmission
// without KHR_materials_volume (a thin wall, which does not bend light); and an animations field
// of the wrong kind, which must be named.
#include <gtest/gtest.h>

#include <fstream>

#include "engine/render_rt/renderer.h"
#include "tests/gltf/gltf_test_dir.h"

namespace rtrt {
namespace {

using test::GltfBuilder;
using Json = nlohmann::json;

GltfBuilder OneTriangle() {
    GltfBuilder b;
    b.Mesh(b.Floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3));
    b.Node({{"mesh", 0}});
    b.doc["scenes"] = Json::array({{{"nodes", {0}}}});
    return b;
}

class GltfSpecTest : public GltfTest {
  protected:
    // B's document with its buffer in a file of its own, FILE (the uri URI decoded by RFC 3986).
    std::string SaveWithExternalBuffer(const GltfBuilder& b, const std::string& uri,
                                       const std::string& file) const {
        Json d = b.doc;
        d["buffers"] = Json::array({{{"byteLength", b.bin.size()}, {"uri", uri}}});
        std::ofstream(dir_ / file, std::ios::binary)
            .write(reinterpret_cast<const char*>(b.bin.data()), std::streamsize(b.bin.size()));
        return Save("external.gltf", d.dump());
    }
};

TEST_F(GltfSpecTest, APlusInAUriIsAPlus) {
    const GltfBuilder b = OneTriangle();
    for (const auto& [uri, file] :
         std::vector<std::pair<std::string, std::string>>{{"only+one.bin", "only+one.bin"},
                                                          {"50%.bin", "50%.bin"},
                                                          {"a%2Bb+c%20d.bin", "a+b+c d.bin"}}) {
        const LoadedScene loaded = LoadSceneFile(SaveWithExternalBuffer(b, uri, file));
        EXPECT_EQ(loaded.scene.blases.size(), 1u) << uri;
    }
    // An image beside a GLB: its uri is rewritten inside the binary container too.
    GltfBuilder t = test::TwoLevels();
    const std::vector<uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    GltfBuilder::Save((dir_ / "tex+1.bmp").string(), GltfBuilder::Bmp(2, 2, rgb));
    t.doc["images"] = Json::array({{{"uri", "tex+1.bmp"}}});
    t.doc["textures"] = Json::array({{{"source", 0}}});
    t.doc["materials"] =
        Json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    t.doc["meshes"][0]["primitives"][0]["material"] = 0;
    t.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
        t.Floats({0, 0, 1, 0, 0, 1}, "VEC2", 2);
    const LoadedScene textured = LoadSceneFile(Save("textured.glb", t.Glb()));
    EXPECT_EQ(textured.scene.textures.size(), 1u);
}

// A GLB whose JSON chunk is followed by a chunk of a type glTF does not define (its buffer a data
// URI): readers must ignore the chunk (tinygltf 2.7 refused the file).
TEST_F(GltfSpecTest, AChunkOfUnknownTypeAfterTheJsonIsIgnored) {
    std::string json = OneTriangle().GltfText();
    while (json.size() % 4) json += ' ';
    std::string glb = "glTF";
    auto u32 = [&](uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
    u32(2);
    u32(uint32_t(12 + 8 + json.size() + 8 + 4));
    u32(uint32_t(json.size()));
    u32(0x4E4F534Au);
    glb += json;
    u32(4);
    u32(0x12345678u);
    glb += "abcd";
    EXPECT_EQ(LoadSceneFile(Save("unknown_chunk.glb", glb)).scene.blases.size(), 1u);
}

TEST_F(GltfSpecTest, AnimationsOfTheWrongKindAreNamed) {
    for (const Json& animations : {Json(5), Json("walk"), Json::object()}) {
        GltfBuilder b = OneTriangle();
        b.doc["animations"] = animations;
        ExpectGltfError(Save("animations.gltf", b.GltfText()), "animations",
                        "expected an array of objects");
    }
}

TEST_F(GltfSpecTest, CamerasTakeAnyAngleAboveZeroAndBelowPi) {
    GltfBuilder b = OneTriangle();
    b.doc["cameras"] = Json::array(
        {{{"type", "perspective"}, {"perspective", {{"yfov", 0.015}, {"znear", 0.1}}}}});
    const int camera = b.Node({{"camera", 0}, {"translation", {0, 0, 500}}});
    b.doc["nodes"][0]["children"] = Json::array({camera});
    const LoadedScene tele = LoadSceneFile(Save("tele.gltf", b.GltfText()));
    EXPECT_NEAR(tele.scene.camera.fovYDegrees, 0.015 * 180.0 / M_PI, 1e-5);
    for (const double yfov : {0.0, -0.5, 3.1416, 1e-4}) {
        b.doc["cameras"][0]["perspective"]["yfov"] = yfov;
        ExpectGltfError(Save("bad_fov.gltf", b.GltfText()), "cameras[0].perspective.yfov",
                        yfov == 1e-4 ? "below 1e-3 radians" : "above 0 and below pi");
    }
}

// A glass sheet at 45 degrees in front of bright bars on black: without KHR_materials_volume it
// is a thin wall, and every pixel shows the bar or the gap it shows without the sheet; as the
// face of a volume (thickness 1) it bends the rays and moves the bars.
TEST_F(GltfSpecTest, TransmissionWithoutAVolumeIsAThinWall) {
    auto render = [&](const char* volume, uint32_t features = kAllFeatures,
                      double specularFactor = 1.0) {
        GltfBuilder b;
        b.Mesh(
            b.Floats({-1.5f, -2, 1.5f, 1.5f, -2, -1.5f, 1.5f, 2, -1.5f, -1.5f, 2, 1.5f}, "VEC3", 3),
            b.Accessor(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, 5123, "SCALAR", 1), -1, 0);
        b.Node({{"mesh", 0}});
        b.doc["scenes"] = Json::array({{{"nodes", {0}}}});
        Json glass = {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}},
                      {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1}}}}},
                      {"doubleSided", true}};
        if (volume) glass["extensions"]["KHR_materials_volume"] = Json::parse(volume);
        glass["extensions"]["KHR_materials_specular"] = {{"specularFactor", specularFactor}};
        b.doc["materials"] = Json::array({glass});
        Save("sheet.gltf", b.GltfText());
        Json scene = Json::parse(R"({
            "camera": {"position": [0, 0, 8], "look_at": [0, 0, 0], "fov_y": 40},
            "background": [0, 0, 0], "lights": [], "max_depth": 2,
            "materials": {"bright": {"diffuse": 0, "specular": 0, "ambient": 1}},
            "models": {"bar": {"type": "box", "size": [0.5, 6, 0.5]},
                       "sheet": {"type": "gltf", "file": "sheet.gltf"}},
            "instances": []})");
        for (int i = -4; i <= 4; ++i)
            scene["instances"].push_back(
                {{"model", "bar"}, {"material", "bright"}, {"position", {i, 0, -4}}});
        Json bare = scene;
        scene["instances"].push_back({{"model", "sheet"}});
        std::ofstream(dir_ / "with.json") << scene.dump();
        std::ofstream(dir_ / "without.json") << bare.dump();
        RenderSettings settings;
        settings.width = settings.height = 64;
        settings.maxDepth = 2;
        settings.enabledFeatures = features;
        const Image with = RenderRaw(LoadSceneFile((dir_ / "with.json").string()).scene, settings);
        const Image without =
            RenderRaw(LoadSceneFile((dir_ / "without.json").string()).scene, settings);
        int moved = 0, behindSheet = 0;
        for (uint32_t y = 0; y < 64; ++y)
            for (uint32_t x = 0; x < 64; ++x) {
                const bool bar = with.At(x, y)[1] > 0.5f, barBefore = without.At(x, y)[1] > 0.5f;
                moved += bar != barBefore;
                behindSheet += with.At(x, y) != without.At(x, y);
            }
        return std::pair(moved, behindSheet);
    };
    const auto [thinMoved, thinCovered] = render(nullptr);
    EXPECT_EQ(thinMoved, 0);
    EXPECT_GT(thinCovered, 500);  // the sheet covers about a fifth of the image
    EXPECT_EQ(render(R"({"thicknessFactor": 0})").first, 0);  // thickness 0 is thin too
    EXPECT_GT(render(R"({"thicknessFactor": 1})").first, 50);
    // Without a Fresnel layer (KHR_materials_specular's factor 0) a thin wall of white glass is
    // not there at all: it reflects nothing and transmits everything (fresnel_mix).
    EXPECT_EQ(render(nullptr, kAllFeatures, 0.0).second, 0);
    // The Blinn-Phong approximation (kernels without the PBR BRDF) passes it unbent too.
    const uint32_t blinnPhong = kAllFeatures & ~kFeaturePbr;
    EXPECT_EQ(render(nullptr, blinnPhong).first, 0);
    EXPECT_GT(render(nullptr, blinnPhong).second, 500);
    EXPECT_GT(render(R"({"thicknessFactor": 1})", blinnPhong).first, 50);
}

}  // namespace
}  // namespace rtrt
