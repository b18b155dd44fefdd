// glTF files made to break the loader: each defect of the hostile corpus (tests/data/hostile_gltf)
// gives one InputError naming its field, a FIFO is refused instead of waited on, and a file's
// images share one budget of texels. Well-formed files: gltf_import_test.cpp.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>

#include "engine/core/error.h"
#include "game/gltf/gltf_image_loader.h"
#include "game/gltf/gltf_import.h"
#include "game/scene/scene_file.h"
#include "tests/gltf/gltf_builder.h"
#include "tests/gltf/gltf_test_dir.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;
using test::GltfBuilder;
using Json = nlohmann::json;

constexpr int kUShort = 5123;

// The file's images share one budget of texels: images can share one buffer view, so a small
// file could ask for any number of large decodes.
TEST(GltfTexelBudget, TheFilesImagesShareOneBudget) {
    GltfImageFailure failure;
    for (int i = 0; i < 4; ++i) EXPECT_EQ(CountGltfTexels(&failure, 16384, 16384), "") << i;
    EXPECT_EQ(failure.texels, kMaxGltfFileTexels);
    EXPECT_NE(CountGltfTexels(&failure, 1, 1).find("past what rtrt reads (2^30 texels together)"),
              std::string::npos);
    EXPECT_EQ(failure.texels, kMaxGltfFileTexels);  // a refused image counts nothing
    GltfImageFailure other;
    EXPECT_EQ(CountGltfTexels(&other, 0, 7), "");
    EXPECT_EQ(other.texels, 0u);
}

// A buffer whose uri names a FIFO is refused instead of waited on.
TEST_F(GltfTest, ABufferThatIsAFifoIsRefused) {
    GltfBuilder b = test::TwoLevels();
    Json d = b.doc;
    d["buffers"] = Json::array({{{"byteLength", b.bin.size()}, {"uri", "fifo.bin"}}});
    ASSERT_EQ(::mkfifo((dir_ / "fifo.bin").c_str(), 0600), 0);
    const std::string path = Save("fifo.gltf", d.dump());
    try {
        LoadSceneFile(path);
        ADD_FAILURE() << "loaded";
    } catch (const InputError& e) {
        EXPECT_EQ(e.File(), path);
        EXPECT_NE(std::string(e.what()).find("fifo.bin"), std::string::npos) << e.what();
    }
}

// Found by probing: material factors and extensions of the wrong JSON type were read as absent
// ("metallicFactor": "0" rendered as metal, "baseColorFactor": "red" as white), and
// componentType 5124, no glTF type, read float positions as integers.
TEST_F(GltfTest, MistypedMaterialFieldsAndUnknownComponentTypesAreRefused) {
    const Json base = Json::parse(test::TwoLevels().GltfText());
    struct Case {
        const char* json;  // merged into materials[0]
        const char* field;
        const char* reason;
    };
    const Case cases[] = {
        {R"({"pbrMetallicRoughness": {"metallicFactor": "0"}})",
         "materials[0].pbrMetallicRoughness.metallicFactor", "expected a number, got string"},
        {R"({"pbrMetallicRoughness": {"baseColorFactor": "red"}})",
         "materials[0].pbrMetallicRoughness.baseColorFactor", "expected an array of 4 numbers"},
        {R"({"emissiveTexture": {"index": 0, "extensions": {"KHR_texture_transform": [1, 2]}}})",
         "materials[0].emissiveTexture.extensions.KHR_texture_transform", "expected an object"},
        {R"({"extensions": {"KHR_materials_ior": 5}})", "materials[0].extensions.KHR_materials_ior",
         "expected an object, got number"},
        {R"({"occlusionTexture": {"index": 0, "strength": true}})",
         "materials[0].occlusionTexture.strength", "expected a number, got boolean"},
    };
    for (const Case& c : cases) {
        Json d = base;
        d["materials"] = Json::array({Json::parse(c.json)});
        ExpectGltfError(Save("material.gltf", d.dump()), c.field, c.reason);
    }
    Json d = base;
    d["extensionsRequired"] = "KHR_texture_basisu";
    ExpectGltfError(Save("required.gltf", d.dump()), "extensionsRequired",
                    "expected an array of strings, got string");
    // Required meshopt compression: refused by name (read as uncompressed, its empty fallback
    // buffers had failed with errors about other fields).
    for (const char* meshopt : {"EXT_meshopt_compression", "KHR_meshopt_compression"}) {
        d = base;
        d["extensionsUsed"] = {meshopt};
        d["extensionsRequired"] = {meshopt};
        ExpectGltfError(Save("meshopt.gltf", d.dump()), "extensionsRequired",
                        std::string(meshopt) +
                            ": the buffers are meshopt-compressed, which rtrt "
                            "cannot decode");
    }
    d = base;
    d["accessors"][0]["componentType"] = 5124;
    ExpectGltfError(Save("int32.gltf", d.dump()), "accessors[0].componentType",
                    "must be 5120, 5121, 5122, 5123, 5125 or 5126");
}

// Fields glTF requires, and its enumerations, are checked by field before tinygltf reads the
// file: its messages named no element ("'count' property is missing in Accessor.") or, for a
// skin without joints, nothing but "could not load the file".
TEST_F(GltfTest, MissingRequiredFieldsAreNamed) {
    const Json base = Json::parse(test::TwoLevels().GltfText());
    struct Case {
        std::function<void(Json&)> edit;
        const char* field;
        const char* reason;
    };
    const Case cases[] = {
        {[](Json& d) { d["accessors"][0].erase("count"); }, "accessors[0].count",
         "missing (glTF 2.0 requires it)"},
        {[](Json& d) { d["accessors"][0]["type"] = "VEC7"; }, "accessors[0].type",
         "expected one of SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3, MAT4, got \"VEC7\""},
        {[](Json& d) {
             d["accessors"][0]["sparse"] = {{"count", 1}};
         },
         "accessors[0].sparse.indices", "missing"},
        {[](Json& d) { d["bufferViews"][0].erase("buffer"); }, "bufferViews[0].buffer", "missing"},
        {[](Json& d) { d["buffers"][0].erase("byteLength"); }, "buffers[0].byteLength", "missing"},
        {[](Json& d) { d["meshes"][0]["primitives"][0].erase("attributes"); },
         "meshes[0].primitives[0].attributes", "missing"},
        {[](Json& d) { d["meshes"][0].erase("primitives"); }, "meshes[0].primitives", "missing"},
        {[](Json& d) { d["skins"] = Json::array({Json::object()}); }, "skins[0].joints", "missing"},
        {[](Json& d) {
             d["cameras"] = Json::array({{{"type", "perspective"}}});
         },
         "cameras[0].perspective", "missing"},
        {[](Json& d) {
             d["cameras"] = Json::array({{{"type", "fisheye"}}});
         },
         "cameras[0].type", "expected one of perspective, orthographic"},
        {[](Json& d) {
             d["cameras"] =
                 Json::array({{{"type", "orthographic"}, {"orthographic", {{"xmag", 1}}}}});
         },
         "cameras[0].orthographic.ymag", "missing"},
        {[](Json& d) { d["images"] = Json::array({Json::object()}); }, "images[0]",
         "give a uri or a bufferView"},
        {[](Json& d) {
             d["animations"] = Json::array(
                 {{{"channels", Json::array({{{"sampler", 0}, {"target", Json::object()}}})},
                   {"samplers", Json::array({{{"input", 0}, {"output", 0}}})}}});
         },
         "animations[0].channels[0].target.path", "missing"},
        {[](Json& d) {
             d["animations"] = Json::array(
                 {{{"channels", Json::array()},
                   {"samplers",
                    Json::array({{{"input", 0}, {"output", 0}, {"interpolation", "CUBIC"}}})}}});
         },
         "animations[0].samplers[0].interpolation", "expected one of LINEAR, STEP, CUBICSPLINE"},
        {[](Json& d) { d["asset"].erase("version"); }, "asset.version", "missing"},
        {[](Json& d) { d.erase("asset"); }, "asset", "missing"},
    };
    for (const Case& c : cases) {
        Json d = base;
        c.edit(d);
        ExpectGltfError(Save("required.gltf", d.dump()), c.field, c.reason);
    }
}

// A buffer file of another size than its byteLength is refused by its size, before it is read:
// a 2 GiB file named for 36 bytes was read whole (and copied) first.
TEST_F(GltfTest, ABufferFileOfAnotherSizeIsRefusedBeforeItIsRead) {
    const GltfBuilder b = test::TwoLevels();
    Json d = b.doc;
    d["buffers"] = Json::array({{{"byteLength", b.bin.size()}, {"uri", "big.bin"}}});
    {
        std::ofstream bin(dir_ / "big.bin", std::ios::binary);
        bin.write(reinterpret_cast<const char*>(b.bin.data()), std::streamsize(b.bin.size()));
    }
    fs::resize_file(dir_ / "big.bin", uint64_t(1) << 33);  // sparse: 8 GiB that a read would take
    ExpectGltfError(Save("big.gltf", d.dump()), "buffers[0].byteLength",
                    "is " + std::to_string(b.bin.size()) + ", but \"" +
                        (dir_ / "big.bin").string() +
                        "\" holds 8589934592 bytes; they must be equal");
}

// A glTF's nodes and primitives count against the scene's 2,000,000 entities before any is made,
// shown alone and placed by a scene file (10 million from a 950 KB file had run out of memory).
TEST_F(GltfTest, NodesAndPrimitivesCountAgainstTheEntityBudgetFirst) {
    GltfBuilder b = test::TwoLevels();
    Json d = b.doc;
    // One mesh of 100 primitives that share an accessor, under 20,000 nodes: 2,020,000 entities.
    const Json primitive = d["meshes"][0]["primitives"][0];
    d["meshes"][0]["primitives"] = Json::array();
    for (int k = 0; k < 100; ++k) d["meshes"][0]["primitives"].push_back(primitive);
    d["nodes"] = Json::array();
    Json roots = Json::array();
    for (int n = 0; n < 20000; ++n) {
        d["nodes"].push_back({{"mesh", 0}});
        roots.push_back(n);
    }
    d["scenes"] = Json::array({{{"nodes", roots}}});
    b.doc = d;
    const std::string path = Save("many.gltf", b.GltfText());
    ExpectGltfError(path, "nodes", "make 2020000 entities; a scene may have at most 2,000,000");
    const std::string scene =
        Save("placed.json", R"({"models": {"g": {"type": "gltf", "file": "many.gltf"}},
                         "instances": [{"model": "g"}]})");
    ExpectGltfError(scene, "instances[0].model", "the scene would have 2020001 entities");
}

// Found by probing: an image no texture uses whose uri is a FIFO made tinygltf wait for ever
// (its own check that a file exists opens it), and extras nested 20,000 deep overflowed the
// stack in tinygltf's recursive reading of JSON values (SIGSEGV).
TEST_F(GltfTest, AnUnusedFifoImageAndDeepNestingAreRefused) {
    Json d = Json::parse(test::TwoLevels().GltfText());
    d["images"] = Json::array({{{"uri", "unused.fifo"}}});
    ASSERT_EQ(::mkfifo((dir_ / "unused.fifo").c_str(), 0600), 0);
    ExpectGltfError(Save("unused_fifo.gltf", d.dump()), "images[0].uri",
                    "unused.fifo\" is not a regular file");
    d.erase("images");
    const std::string text = d.dump();
    const std::string deep = text.substr(0, text.size() - 1) +
                             ", \"extras\": " + std::string(20000, '[') + std::string(20000, ']') +
                             "}";
    ExpectGltfError(Save("deep.gltf", deep), "", "nested more than 256 levels deep");
    // Brackets inside strings are text, not nesting.
    d["asset"]["extras"] = {{"note", std::string(1000, '[')}};
    EXPECT_NO_THROW(LoadSceneFile(Save("brackets.gltf", d.dump())));
}

// Found by probing: a data URI whose size is not the buffer's byteLength, a uri naming a folder
// or an absolute path, and camera aspect ratios glTF forbids or no image can have each had
// tinygltf's raw message (or none) instead of the field and the reason.
TEST_F(GltfTest, BufferUrisAndCameraAspectsAreCheckedByField) {
    const GltfBuilder b = test::TwoLevels();
    Json d = Json::parse(b.GltfText());
    d["buffers"][0]["byteLength"] = b.bin.size() + 4;
    ExpectGltfError(Save("long.gltf", d.dump()), "buffers[0].byteLength",
                    std::to_string(b.bin.size() + 4) + ", but the data URI holds " +
                        std::to_string(b.bin.size()) + " bytes");
    d["buffers"][0]["byteLength"] = b.bin.size();
    d["buffers"][0]["uri"] = "data:application/octet-stream;base64,AA*A";
    ExpectGltfError(Save("not_base64.gltf", d.dump()), "buffers[0].uri", "not base64");
    d["buffers"][0]["uri"] = "data:application/octet-stream;base64,";
    d["buffers"][0]["byteLength"] = 0;
    ExpectGltfError(Save("empty.gltf", d.dump()), "buffers[0].uri", "holds no data");

    Json external = b.doc;
    external["buffers"] = Json::array({{{"byteLength", b.bin.size()}, {"uri", "folder.bin"}}});
    fs::create_directories(dir_ / "folder.bin");
    ExpectGltfError(Save("folder.gltf", external.dump()), "buffers[0].uri",
                    "is not a regular file");
    fs::create_symlink("loop_b.bin", dir_ / "loop_a.bin");  // a loop of links is named so
    fs::create_symlink("loop_a.bin", dir_ / "loop_b.bin");
    external["buffers"][0]["uri"] = "loop_a.bin";
    ExpectGltfError(Save("loop.gltf", external.dump()), "buffers[0].uri",
                    "Too many levels of symbolic links");
    external["buffers"][0]["uri"] = "/etc/hostname";
    ExpectGltfError(Save("absolute.gltf", external.dump()), "buffers[0].uri",
                    "is an absolute path");

    // A file with one camera of this aspect ratio, on a child of the root.
    auto withAspect = [&](double aspect) {
        GltfBuilder c = test::TwoLevels();
        c.doc["cameras"] = Json::array(
            {{{"type", "perspective"},
              {"perspective", {{"yfov", 0.5}, {"znear", 0.1}, {"aspectRatio", aspect}}}}});
        c.doc["nodes"][0]["children"].push_back(c.Node({{"camera", 0}}));
        return Save("aspect.gltf", c.GltfText());
    };
    for (const double aspect : {0.0, -1.5})
        ExpectGltfError(withAspect(aspect), "cameras[0].perspective.aspectRatio", "greater than 0");
    // The image of a glTF shown on its own: 1280 columns, 1280 / aspect rows within 1 to 16384.
    // (1e-30: 1280 / aspect is beyond lround's range, which had made 1 row.)
    const std::pair<double, uint32_t> rows[] = {
        {2.0, 640u}, {1e6, 1u}, {1e-6, 16384u}, {1e-30, 16384u}};
    for (const auto& [aspect, height] : rows) {
        const LoadedScene loaded = LoadSceneFile(withAspect(aspect));
        EXPECT_EQ(loaded.width, 1280u) << aspect;
        EXPECT_EQ(loaded.height, height) << aspect;
    }
}

// glTF's bounds that tinygltf does not check or reports without the field.
TEST_F(GltfTest, SchemaBoundsAreCheckedByField) {
    const struct {
        const char* name;
        void (*edit)(Json& d);
        const char* field;
        const char* reason;
    } cases[] = {
        {"negative_offset.gltf", [](Json& d) { d["accessors"][0]["byteOffset"] = -4; },
         "accessors[0].byteOffset", "must be at least 0, got -4"},
        {"odd_stride.gltf", [](Json& d) { d["bufferViews"][0]["byteStride"] = 13; },
         "bufferViews[0].byteStride", "multiple of 4 from 4 to 252, got 13"},
        {"negative_length.gltf", [](Json& d) { d["bufferViews"][0]["byteLength"] = -1; },
         "bufferViews[0].byteLength", "must be at least 0"},
        {"version_3.gltf", [](Json& d) { d["asset"]["version"] = "3.0"; }, "asset.version",
         "rtrt reads glTF 2.x"},
    };
    for (const auto& c : cases) {
        Json d = Json::parse(test::TwoLevels().GltfText());
        c.edit(d);
        ExpectGltfError(Save(c.name, d.dump()), c.field, c.reason);
    }
    // A byteStride of 0, below glTF's minimum but common in exported files, reads as packed.
    Json packed = Json::parse(test::TwoLevels().GltfText());
    packed["bufferViews"][0]["byteStride"] = 0;
    EXPECT_NO_THROW(LoadSceneFile(Save("stride_0.gltf", packed.dump())));
}

// A camera and a spot light under ancestors scaled 1e10 each: the world transform is finite, its
// directions' lengths are not; they still come out as unit vectors along the node's axes.
TEST_F(GltfTest, HugeScalesStillGiveUnitDirections) {
    GltfBuilder b = test::TwoLevels();
    b.doc["cameras"] =
        Json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.01}}}}});
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
        Json::array({{{"type", "spot"}, {"spot", {{"outerConeAngle", 0.5}}}}});
    b.Node({{"scale", {1e10, 1e10, 1e10}}, {"children", {3}}});
    b.Node({{"scale", {1e10, 1e10, 1e10}},
            {"camera", 0},
            {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.doc["scenes"][0]["nodes"].push_back(2);
    const LoadedScene loaded = LoadSceneFile(Save("huge_scale.gltf", b.GltfText()));
    const Camera& c = loaded.scene.camera;
    EXPECT_NEAR(glm::length(c.forward - vec3(0, 0, -1)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(c.up - vec3(0, 1, 0)), 0.0f, 1e-6f);
    ASSERT_EQ(loaded.scene.lights.size(), 1u);
    EXPECT_NEAR(glm::length(loaded.scene.lights[0].spotAxis - vec3(0, 0, -1)), 0.0f, 1e-6f);
}

// Each defect gives one InputError naming the field, and no warning before it.
struct HostileGltf {
    std::string name;
    std::string bytes;
    std::string field;
    std::string reason;
};

std::vector<HostileGltf> MakeHostileGltfCorpus() {
    const GltfBuilder base = test::TwoLevels();
    const std::string glb = base.Glb();
    auto edit = [&](auto change) {
        GltfBuilder b = base;
        change(b);
        return b.GltfText();
    };
    auto binary = [&](auto change) {
        GltfBuilder b = base;
        change(b);
        return b.Glb();
    };
    const float nan = std::nanf(""), inf = INFINITY;
    std::string badVersion = glb;
    badVersion[4] = 1;
    std::string shortChunk = glb;
    shortChunk[12] = char(0xff);  // JSON chunk length beyond the file
    shortChunk[13] = char(0xff);
    return {
        {"truncated.glb", glb.substr(0, glb.size() - 10), "header.length", "(truncated)"},
        {"truncated_header.glb", glb.substr(0, 7), "header", "truncated"},
        {"no_chunks.glb", std::string("glTF\x02\0\0\0\x0c\0\0\0", 12), "chunks",
         "needs a JSON chunk"},
        {"wrong_magic.glb", "gLTF" + glb.substr(4), "header.magic", "not a GLB file"},
        {"wrong_version.glb", badVersion, "header.version", "GLB version 1"},
        {"chunk_too_long.glb", shortChunk, "chunks[0].length", "do not fit"},
        {"huge_count.gltf",
         edit([](GltfBuilder& b) { b.doc["accessors"][0]["count"] = 1000000000; }),
         "accessors[0].count", "do not fit in buffer view"},
        {"view_outside_buffer.gltf",
         edit([](GltfBuilder& b) { b.doc["bufferViews"][0]["byteLength"] = 4000; }),
         "bufferViews[0].byteLength", "outside buffer"},
        {"nan_position.glb",
         binary([&](GltfBuilder& b) { std::memcpy(b.bin.data() + 16, &nan, 4); }),
         "meshes[0].primitives[0].attributes.POSITION", "NaN or infinite"},
        {"inf_position.gltf", edit([&](GltfBuilder& b) { std::memcpy(b.bin.data(), &inf, 4); }),
         "meshes[0].primitives[0].attributes.POSITION", "NaN or infinite"},
        {"inf_translation.gltf", edit([](GltfBuilder& b) {
             b.doc["nodes"][1]["translation"] = {0, 1e39, 0};
         }),
         "nodes[1].translation", "NaN or infinite"},
        {"nan_matrix.gltf", edit([](GltfBuilder& b) {
             b.doc["nodes"][0].erase("rotation");
             b.doc["nodes"][0].erase("translation");
             b.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1e300, 0, 1};
         }),
         "nodes[0].matrix", "NaN or infinite"},
        {"index_out_of_range.gltf", edit([](GltfBuilder& b) {
             const int idx = b.Accessor(std::vector<uint16_t>{0, 1, 7}, kUShort, "SCALAR", 1);
             b.doc["meshes"][0]["primitives"][0]["indices"] = idx;
         }),
         "meshes[0].primitives[0].indices", "out of range (3 vertices)"},
        {"cyclic_nodes.gltf", edit([](GltfBuilder& b) {
             b.doc["nodes"][1]["children"] = {2};
             b.Node({{"children", {1}}});
         }),
         "nodes[2].children[0]", "has two parents"},
        {"cycle_without_root.gltf", edit([](GltfBuilder& b) {
             b.Node({{"children", {3}}});
             b.Node({{"children", {2}}});
         }),
         "nodes[2].children", "its own ancestor"},
        {"own_child.gltf", edit([](GltfBuilder& b) { b.doc["nodes"][1]["children"] = {1}; }),
         "nodes[1].children[0]", "its own child"},
        {"missing_buffer.gltf",
         [&] {
             Json d = Json::parse(base.GltfText());
             d["buffers"][0]["uri"] = "no_such.bin";
             return d.dump();
         }(),
         "buffers[0].uri", "no such file"},
        {"missing_image.gltf", edit([](GltfBuilder& b) {
             b.doc["images"] = Json::array({{{"uri", "no_such.png"}}});
             b.doc["textures"] = Json::array({{{"source", 0}}});  // used: it must be there
         }),
         "images[0].uri", "no such file"},
        {"wrong_type.gltf", edit([](GltfBuilder& b) { b.doc["nodes"][1]["mesh"] = 7; }),
         "nodes[1].mesh", "out of range"},
        {"not_json.gltf", "{ \"asset\": ", "", "malformed JSON"},
        {"wrong_json_type.gltf",
         edit([](GltfBuilder& b) { b.doc["nodes"][1]["translation"] = "up"; }),
         "nodes[1].translation", "expected an array of 3 numbers, got string"},
        {"nodes_not_array.gltf", edit([](GltfBuilder& b) { b.doc["nodes"] = 5; }), "nodes",
         "expected an array of objects"},
        {"bad_accessor_type.gltf",
         edit([](GltfBuilder& b) { b.doc["accessors"][0]["type"] = "VEC2"; }), "accessors[0].type",
         "wrong element type"},
        {"texture_transform_not_number.gltf", edit([](GltfBuilder& b) {
             b.doc["textures"] = Json::array({Json::object()});
             b.doc["materials"] =
                 Json::array({{{"pbrMetallicRoughness",
                                {{"baseColorTexture",
                                  {{"index", 0},
                                   {"extensions",
                                    {{"KHR_texture_transform", {{"offset", {"left", 0}}}}}}}}}}}});
             b.doc["meshes"][0]["primitives"][0]["material"] = 0;
         }),
         "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform."
         "offset",
         "expected a number"},
        {"normal_texture_out_of_range.gltf", edit([](GltfBuilder& b) {
             b.doc["materials"] = Json::array({{{"normalTexture", {{"index", 5}}}}});
             b.doc["meshes"][0]["primitives"][0]["material"] = 0;
         }),
         "materials[0].normalTexture.index", "out of range"},
        {"spot_cone_inverted.gltf", edit([](GltfBuilder& b) {
             b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
                 Json::array({{{"type", "spot"},
                               {"spot", {{"innerConeAngle", 0.8}, {"outerConeAngle", 0.5}}}}});
         }),
         "extensions.KHR_lights_punctual.lights[0].spot.innerConeAngle", "below outerConeAngle"},
        // Each translation is within a float's range, their sum is not: the light has no place.
        {"light_overflow.gltf", edit([](GltfBuilder& b) {
             b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
                 Json::array({{{"type", "point"}}});
             b.Node({{"translation", {3e38, 0, 0}}, {"children", {3}}});
             b.Node({{"translation", {3e38, 0, 0}},
                     {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
             b.doc["scenes"][0]["nodes"].push_back(2);
         }),
         "nodes[3]", "world transform overflows a float"},
        {"negative_light_range.gltf", edit([](GltfBuilder& b) {
             b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
                 Json::array({{{"type", "point"}, {"range", -2}}});
         }),
         "extensions.KHR_lights_punctual.lights[0].range", "must be positive (or 0"},
        // A Draco primitive whose stream is not one (the positions' own bytes); the reason names
        // libdraco with or without it ("cannot decode" or "built without").
        {"draco_not_a_stream.glb", binary([](GltfBuilder& b) {
             b.doc["accessors"][0].erase("bufferView");
             b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {
                 {"bufferView", 0}, {"attributes", {{"POSITION", 0}}}};
             b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
         }),
         "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression", "libdraco"},
        {"draco_view_out_of_range.gltf", edit([](GltfBuilder& b) {
             b.doc["accessors"][0].erase("bufferView");
             b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {
                 {"bufferView", 3}, {"attributes", {{"POSITION", 0}}}};
         }),
         "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression.bufferView",
         "names no buffer view"},
    };
}

TEST_F(GltfTest, EveryHostileFileGivesOneError) {
    for (const HostileGltf& c : MakeHostileGltfCorpus()) {
        const std::string path = Save(c.name, c.bytes);
        ::testing::internal::CaptureStderr();
        try {
            LoadSceneFile(path);
            ADD_FAILURE() << c.name << ": loaded without an error";
        } catch (const InputError& e) {
            EXPECT_EQ(e.File(), path) << c.name;
            if (!c.field.empty()) {
                EXPECT_EQ(e.Field(), c.field) << c.name << ": " << e.what();
            }
            EXPECT_NE(e.Reason().find(c.reason), std::string::npos) << c.name << ": " << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << c.name;
        }
        EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << c.name;
    }
}

// The committed corpus (tests/data/hostile_gltf/, read by the CLI test and seeding the fuzzer)
// is this generator's output. To write it again:
// RTRT_WRITE_HOSTILE_CORPUS=1 rtrt_gltf_tests --gtest_filter='*CommittedHostileGltf*'
TEST_F(GltfTest, CommittedHostileGltfCorpusIsCurrent) {
    const std::string corpus = test::SourcePath("tests/data/hostile_gltf");
    const bool write = std::getenv("RTRT_WRITE_HOSTILE_CORPUS") != nullptr;
    if (write) {
        fs::create_directories(corpus);
        GltfBuilder::Save(corpus + "/valid.glb", test::TwoLevels().Glb());
        GltfBuilder::Save(corpus + "/valid.gltf", test::TwoLevels().GltfText());
    }
    EXPECT_NO_THROW(LoadSceneFile(corpus + "/valid.glb"));
    for (const HostileGltf& c : MakeHostileGltfCorpus()) {
        const std::string path = corpus + "/" + c.name;
        if (write) GltfBuilder::Save(path, c.bytes);
        std::ifstream in(path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), {});
        EXPECT_EQ(bytes, c.bytes) << path << " is stale; see this test's comment";
        EXPECT_THROW(LoadSceneFile(path), InputError) << path;
    }
}

}  // namespace
}  // namespace rtrt
