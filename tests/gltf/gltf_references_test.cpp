// References between a glTF file's objects and the enumerations of its samplers and materials,
// checked before tinygltf reads the file (gltf_references.h), and the warning for textures a
// primitive cannot apply, and colour factors above 1. Found by probing: an image's buffer view 1 GB
// past its buffer crashed the decoder; an index of 2^32 named object 0 and a negative one read as
// absent; a wrap mode of 12345 repeated.
#include <gtest/gtest.h>

#include <functional>

#include "engine/core/error.h"
#include "game/scene/scene_file.h"
#include "tests/gltf/gltf_builder.h"
#include "tests/gltf/gltf_test_dir.h"

namespace rtrt {
namespace {

using test::GltfBuilder;
using Json = nlohmann::json;

constexpr uint64_t k2To32 = uint64_t(1) << 32;

// The textured quad with a 1x1 BMP image in its buffer, at the view's own bytes.
GltfBuilder QuadWithImageView() {
    GltfBuilder b = test::TexturedQuadScene(9728, 33071);
    b.ImageInBuffer(GltfBuilder::Bmp(1, 1, {200, 100, 50}), "image/bmp");
    return b;
}

TEST_F(GltfTest, AnImagesBufferViewMustLieInsideItsBuffer) {
    GltfBuilder b = QuadWithImageView();
    ASSERT_NO_THROW(LoadSceneFile(Save("inside.glb", b.Glb())));
    const size_t view = b.doc["bufferViews"].size() - 1;
    const std::string field = "bufferViews[" + std::to_string(view) + "].byteLength";
    b.doc["bufferViews"][view]["byteOffset"] = 1000000000;
    for (const std::string& name : {"far.glb", "far.gltf"})
        ExpectGltfError(Save(name, name.ends_with("glb") ? b.Glb() : b.GltfText()), field,
                        "lie outside buffer 0 of " + std::to_string(b.bin.size()) + " bytes");
    b.doc["bufferViews"][view]["byteOffset"] = 0;
    b.doc["bufferViews"][view]["byteLength"] = b.bin.size() + 1;  // runs past the end
    ExpectGltfError(Save("long.glb", b.Glb()), field, "lie outside buffer 0");
}

TEST_F(GltfTest, AnIndexMustNameAnObjectOfItsArray) {
    GltfBuilder quad = QuadWithImageView();
    const Json base = Json::parse(quad.GltfText());
    struct Case {
        std::function<void(Json&)> edit;
        const char* field;
        std::string reason;
    };
    const Case cases[] = {
        {[](Json& d) { d["textures"][0]["source"] = k2To32; }, "textures[0].source",
         "image 4294967296 out of range (the file has 1 in images)"},
        {[](Json& d) { d["textures"][0]["sampler"] = k2To32 + 1; }, "textures[0].sampler",
         "sampler 4294967297 out of range"},
        {[](Json& d) { d["materials"][0]["emissiveTexture"]["index"] = -3; },
         "materials[0].emissiveTexture.index",
         "texture -3 out of range (the file has 1 in textures)"},
        {[](Json& d) { d["meshes"][0]["primitives"][0]["material"] = k2To32; },
         "meshes[0].primitives[0].material", "material 4294967296 out of range"},
        {[](Json& d) { d["meshes"][0]["primitives"][0]["material"] = "0"; },
         "meshes[0].primitives[0].material", "expected an index (an integer), got string"},
        {[](Json& d) { d["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 99; },
         "meshes[0].primitives[0].attributes.NORMAL", "accessor 99 out of range"},
        {[](Json& d) {
             d["skins"] = Json::array({{{"joints", {0, 7}}}});
         },
         "skins[0].joints[1]", "node 7 out of range (the file has 3 in nodes)"},
        {[](Json& d) {
             d["scenes"][0]["nodes"] = {0, -1};
         },
         "scenes[0].nodes[1]", "node -1 out of range"},
        {[](Json& d) { d["scene"] = 1; }, "scene", "scene 1 out of range"},
        {[](Json& d) {
             d["animations"] = Json::array(
                 {{{"channels",
                    Json::array({{{"sampler", 2}, {"target", {{"node", 0}, {"path", "scale"}}}}})},
                   {"samplers", Json::array({{{"input", 0}, {"output", 0}}})}}});
         },
         "animations[0].channels[0].sampler",
         "sampler 2 out of range (the file has 1 in animations[0].samplers)"},
        {[](Json& d) { d["materials"][0]["emissiveTexture"]["texCoord"] = -1; },
         "materials[0].emissiveTexture.texCoord", "must be a set index from 0, got -1"},
        {[](Json& d) { d["materials"][0]["emissiveTexture"]["texCoord"] = k2To32; },
         "materials[0].emissiveTexture.texCoord", "must be a set index from 0, got 4294967296"},
    };
    for (const Case& c : cases) {
        Json d = base;
        c.edit(d);
        ExpectGltfError(Save("index.gltf", d.dump()), c.field, c.reason);
    }
}

TEST_F(GltfTest, SamplerAndAlphaModeEnumerationsAreChecked) {
    const Json base = Json::parse(QuadWithImageView().GltfText());
    struct Case {
        const char* key;
        Json value;
        const char* field;
        const char* reason;
    };
    const Case cases[] = {
        {"wrapS", 12345, "samplers[0].wrapS", "expected one of 33071, 33648, 10497, got 12345"},
        {"wrapT", "33071", "samplers[0].wrapT", "expected an integer, got string"},
        {"magFilter", 9984, "samplers[0].magFilter", "expected one of 9728, 9729, got 9984"},
        {"minFilter", 1, "samplers[0].minFilter",
         "expected one of 9728, 9729, 9984, 9985, 9986, 9987, got 1"},
    };
    for (const Case& c : cases) {
        Json d = base;
        d["samplers"][0][c.key] = c.value;
        ExpectGltfError(Save("sampler.gltf", d.dump()), c.field, c.reason);
    }
    Json d = base;
    d["materials"][0]["alphaMode"] = "FOO";
    ExpectGltfError(Save("alpha.gltf", d.dump()), "materials[0].alphaMode",
                    "expected one of OPAQUE, MASK, BLEND, got \"FOO\"");
}

// glTF bounds a base colour's and an emission's factors to [0, 1]: a negative component is
// refused; one above 1, which exporters have written (three.js before r129), is taken as 1 with a
// warning, as other viewers load such files.
TEST_F(GltfTest, ColourFactorsAreBetweenZeroAndOne) {
    const Json base = Json::parse(QuadWithImageView().GltfText());
    Json d = base;
    d["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1, 1, 1, -7};
    ExpectGltfError(Save("alpha.gltf", d.dump()),
                    "materials[0].pbrMetallicRoughness.baseColorFactor",
                    "must be between 0 and 1000000, got -7");
    d = base;
    d["materials"][0]["emissiveFactor"] = {1, 1.5, 0.25};
    d["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {5, 0.5, 1, 1};
    ::testing::internal::CaptureStderr();
    const LoadedScene loaded = LoadSceneFile(Save("bright.gltf", d.dump()));
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("materials[0].emissiveFactor: components above 1 (glTF's bound) are taken "
                       "as 1, e.g. 1.5"),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("materials[0].pbrMetallicRoughness.baseColorFactor: components above 1"),
              std::string::npos)
        << err;
    const PbrMaterial& p = loaded.scene.pbrMaterials.at(0);
    EXPECT_EQ(p.baseColor, vec3(1.0f, 0.5f, 1.0f));
    EXPECT_EQ(p.emissive, vec3(1.0f, 1.0f, 0.25f));
}

// tinygltf reads other data URIs as file names: the image was "missing or could not be
// decoded" though its bytes were there.
TEST_F(GltfTest, ADataUriOfATypeNotReadIsNamed) {
    GltfBuilder b = test::TexturedQuadScene(9728, 33071);
    const std::string bmp = GltfBuilder::Bmp(1, 1, {200, 100, 50});
    b.doc["images"] =
        Json::array({{{"uri", "data:image/webp;base64," + GltfBuilder::Base64(std::vector<uint8_t>(
                                                              bmp.begin(), bmp.end()))}}});
    ExpectGltfError(Save("webp.gltf", b.GltfText()), "images[0].uri",
                    "a data URI of type \"image/webp\", which rtrt does not read");
}

// A textured material on a primitive without texture coordinates is told of, naming it.
TEST_F(GltfTest, TexturesWithoutCoordinatesAreWarnedOf) {
    GltfBuilder b = QuadWithImageView();
    b.doc["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
    ::testing::internal::CaptureStderr();
    LoadSceneFile(Save("no_uv.glb", b.Glb()));
    const std::string noUv = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(noUv.find("meshes[0].primitives[0]: its material has textures, but the primitive "
                        "has no TEXCOORD_0"),
              std::string::npos)
        << noUv;
    // The extensions' textures count too: a transmissionTexture alone.
    b.doc["materials"][0] = {
        {"extensions",
         {{"KHR_materials_transmission",
           {{"transmissionFactor", 1.0}, {"transmissionTexture", {{"index", 0}}}}}}}};
    ::testing::internal::CaptureStderr();
    LoadSceneFile(Save("no_uv_transmission.glb", b.Glb()));
    const std::string transmission = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(transmission.find("but the primitive has no TEXCOORD_0"), std::string::npos)
        << transmission;
}

}  // namespace
}  // namespace rtrt
