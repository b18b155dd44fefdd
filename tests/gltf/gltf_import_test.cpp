// glTF import, checked against small files the tests write with known answers: every index type
// gives the same mesh, node hierarchies and animations give the
// expected world transforms, lights and cameras land where their nodes are; and Debian's
// assimp-testmodels load (skipped when the package is missing). Skins and morph targets:
// gltf_deform_test.cpp; materials and textures: gltf_materials_test.cpp.
#include "game/gltf/gltf_import.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.h"
#include "engine/physics_anim/transform.h"
#include "engine/render_rt/renderer.h"
#include "game/gltf/gltf_meshes.h"
#include "game/runtime/world.h"
#include "game/scene/scene_file.h"
#include "tests/gltf/gltf_builder.h"
#include "tests/gltf/gltf_test_dir.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;
using test::GltfBuilder;
using Json = nlohmann::json;

constexpr int kFloat = 5126, kUByte = 5121, kUShort = 5123, kUInt = 5125;

// Either build's decoder (OpenImageIO, or stb without it) names the image it could not decode.
TEST_F(GltfTest, UndecodableImageIsNamed) {
    GltfBuilder b = test::TexturedQuadScene(9728, 33071);
    b.doc["images"] = Json::array(
        {{{"uri", "data:image/png;base64," + GltfBuilder::Base64({'n', 'o', 'p', 'e'})}}});
    const std::string path = Save("undecodable.gltf", b.GltfText());
    try {
        LoadSceneFile(path);
        ADD_FAILURE() << "loaded without an error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.Field(), "images[0]") << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
}

// The same quad with each index type, and without indices.
TEST_F(GltfTest, EveryIndexTypeGivesTheSameMesh) {
    const std::vector<float> corners = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const std::vector<uint32_t> order = {0, 1, 2, 0, 2, 3};
    std::vector<float> unrolled;
    for (uint32_t i : order) unrolled.insert(unrolled.end(), &corners[3 * i], &corners[3 * i + 3]);
    std::vector<std::vector<Triangle>> meshes;
    for (int type : {kUByte, kUShort, kUInt, 0}) {
        GltfBuilder b;
        int mesh;
        if (type == 0) {
            mesh = b.Mesh(b.Floats(unrolled, "VEC3", 3));
        } else {
            const int pos = b.Floats(corners, "VEC3", 3);
            int idx;
            if (type == kUByte)
                idx = b.Accessor(std::vector<uint8_t>(order.begin(), order.end()), kUByte, "SCALAR",
                                 1);
            else if (type == kUShort)
                idx = b.Accessor(std::vector<uint16_t>(order.begin(), order.end()), kUShort,
                                 "SCALAR", 1);
            else
                idx = b.Accessor(order, kUInt, "SCALAR", 1);
            mesh = b.Mesh(pos, idx);
        }
        b.Node({{"mesh", mesh}});
        const LoadedScene loaded =
            LoadSceneFile(Save("q" + std::to_string(type) + ".glb", b.Glb()));
        ASSERT_EQ(loaded.scene.blases.size(), 1u);
        const Blas& blas = *loaded.scene.blases[0];
        std::vector<Triangle> tris(2);
        for (uint32_t slot = 0; slot < blas.PrimCount(); ++slot)
            tris[blas.primIds[slot]] = blas.triangles[slot];
        meshes.push_back(tris);
    }
    for (size_t m = 1; m < meshes.size(); ++m)
        for (size_t t = 0; t < 2; ++t) {
            EXPECT_EQ(meshes[m][t].v0, meshes[0][t].v0) << m;
            EXPECT_EQ(meshes[m][t].v1, meshes[0][t].v1) << m;
            EXPECT_EQ(meshes[m][t].v2, meshes[0][t].v2) << m;
        }
    EXPECT_EQ(meshes[0][1].v2, vec3(-1, 1, 0));
}

TEST_F(GltfTest, NodeHierarchyGivesWorldTransforms) {
    const LoadedScene loaded = LoadSceneFile(Save("tree.gltf", test::TwoLevels().GltfText()));
    ASSERT_EQ(loaded.scene.instances.size(), 1u);
    ASSERT_EQ(loaded.entities.size(), 3u);  // two nodes and the child's primitive
    EXPECT_EQ(loaded.entities[1].parent, 0);
    EXPECT_EQ(loaded.entities[2].parent, 1);
    const vec3 p = loaded.scene.instances[0].ObjectToWorld().Point(vec3(1, 0, 0));
    EXPECT_NEAR(p.x, 3.0f, 1e-5f);
    EXPECT_NEAR(p.y, 0.0f, 1e-5f);
    EXPECT_NEAR(p.z, -2.0f, 1e-5f);
    // The runtime links the same entities and derives the same world transform.
    World world(loaded);
    const vec3 q = world.Scene().instances[0].ObjectToWorld().Point(vec3(1, 0, 0));
    EXPECT_NEAR(glm::length(q - vec3(3, 0, -2)), 0.0f, 1e-5f);
    world.Advance(0.5f);
    const vec3 r = world.Scene().instances[0].ObjectToWorld().Point(vec3(1, 0, 0));
    EXPECT_NEAR(glm::length(r - vec3(3, 0, -2)), 0.0f, 1e-5f);
}

// scene.nodes listing a child: shown once under its parent when the parent's tree is shown,
// as a root of its own when it is not (files that common engines load), with a warning.
TEST_F(GltfTest, SceneNodesListingAChildShowItOnce) {
    GltfBuilder both = test::TwoLevels();
    both.doc["scenes"] = Json::array({{{"nodes", {0, 1}}}});
    const LoadedScene shownUnder = LoadSceneFile(Save("both.gltf", both.GltfText()));
    ASSERT_EQ(shownUnder.scene.instances.size(), 1u);
    const vec3 p = shownUnder.scene.instances[0].ObjectToWorld().Point(vec3(1, 0, 0));
    EXPECT_NEAR(glm::length(p - vec3(3, 0, -2)), 0.0f, 1e-5f);  // under its parent

    GltfBuilder child = test::TwoLevels();
    child.doc["scenes"] = Json::array({{{"nodes", {1}}}});
    const LoadedScene alone = LoadSceneFile(Save("child.gltf", child.GltfText()));
    ASSERT_EQ(alone.scene.instances.size(), 1u);
    const vec3 q = alone.scene.instances[0].ObjectToWorld().Point(vec3(1, 0, 0));
    EXPECT_NEAR(glm::length(q - vec3(2, 0, 2)), 0.0f, 1e-5f);  // its own transform only
}

// A root listed again is shown once, with a warning: a 21 KB file listing one tree a thousand
// times made a million entities.
TEST_F(GltfTest, ARootListedAgainIsShownOnce) {
    GltfBuilder b = test::TwoLevels();
    b.doc["scenes"] = Json::array({{{"nodes", Json::array({0, 0, 0, 0})}}});
    ::testing::internal::CaptureStderr();
    const LoadedScene loaded = LoadSceneFile(Save("repeated.gltf", b.GltfText()));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find("scenes[0].nodes[1]: node 0 is listed again; it is shown once"),
              std::string::npos)
        << warnings;
    EXPECT_EQ(loaded.scene.instances.size(), 1u);
    EXPECT_EQ(loaded.entities.size(), 3u);  // the two nodes and the primitive
}

// Thousands of listed children at the end of a long chain of unlisted nodes: each is shown as a
// root (no ancestor of it is listed), and the loader settles each ancestor once instead of
// walking the chain and searching the list per child (hours for files a few MB long).
TEST_F(GltfTest, ManyListedChildrenOfALongChainAreEachShownOnce) {
    constexpr int kChain = 6000;
    constexpr int kChildren = 6000;
    GltfBuilder b = test::TwoLevels();
    const int mesh = 0;
    b.doc["nodes"] = Json::array();
    for (int i = 0; i < kChain; ++i) b.Node({{"children", {i + 1 < kChain ? i + 1 : kChain}}});
    Json listed = Json::array();
    for (int c = 0; c < kChildren; ++c) {
        listed.push_back(b.Node({{"mesh", mesh}, {"translation", {c, 0, 0}}}));
    }
    b.doc["nodes"][kChain - 1]["children"] = listed;
    b.doc["scenes"] = Json::array({{{"nodes", listed}}});
    ::testing::internal::CaptureStderr();
    const LoadedScene loaded = LoadSceneFile(Save("chain.gltf", b.GltfText()));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find("shown as a root"), std::string::npos) << warnings;
    ASSERT_EQ(loaded.scene.instances.size(), size_t(kChildren));
    const vec3 p = loaded.scene.instances.back().ObjectToWorld().Point(vec3(0.0f));
    EXPECT_NEAR(glm::length(p - vec3(kChildren - 1, 0, 0)), 0.0f, 1e-3f);
}

// Strips and fans become the triangles the specification numbers (3.7.2.1), in one winding;
// the degenerate triangles strips use to restart are left out.
TEST(GltfPrimitiveModes, StripsAndFansGiveTheSpecificationsTriangles) {
    EXPECT_EQ(StripOrFanTriangles({0, 1, 2, 3, 4}, false),
              (std::vector<glm::uvec3>{{0, 1, 2}, {1, 3, 2}, {2, 3, 4}}));
    EXPECT_EQ(StripOrFanTriangles({0, 1, 2, 3, 4}, true),
              (std::vector<glm::uvec3>{{1, 2, 0}, {2, 3, 0}, {3, 4, 0}}));
    // A restart: 0 1 2 2 3 3 4 5 repeats vertices; only the real triangles stay.
    EXPECT_EQ(StripOrFanTriangles({0, 1, 2, 2, 3, 4}, false),
              (std::vector<glm::uvec3>{{0, 1, 2}, {2, 4, 3}}));
    EXPECT_TRUE(StripOrFanTriangles({0, 1}, false).empty());
}

TEST_F(GltfTest, TriangleStripPrimitiveIsTraced) {
    GltfBuilder b;
    const int mesh = b.Mesh(b.Floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, "VEC3", 3));
    b.doc["meshes"][size_t(mesh)]["primitives"][0]["mode"] = 5;
    b.Node({{"mesh", mesh}});
    b.doc["scenes"] = Json::array({{{"nodes", {0}}}});
    const LoadedScene loaded = LoadSceneFile(Save("strip.gltf", b.GltfText()));
    ASSERT_EQ(loaded.scene.instances.size(), 1u);
    EXPECT_EQ(loaded.scene.TriangleCount(), 2u);  // a quad from a 4-vertex strip
}

// An image no texture's own source names — here a KTX2 image that only KHR_texture_basisu's
// source names, and an unreferenced one — is not decoded: the file loads (with a warning), and
// the texture samples its core source.
TEST_F(GltfTest, ImagesOnlyAnExtensionUsesDoNotFailTheFile) {
    GltfBuilder b = test::TexturedQuadScene(9728, 10497);
    const std::string bmp = GltfBuilder::Bmp(1, 1, {200, 100, 50});
    const std::string garbage = "\xabKTX 20\xbb\r\n\x1a\n not really a KTX2 file";
    auto uri = [](const std::string& mime, const std::string& bytes) {
        return "data:" + mime + ";base64," +
               GltfBuilder::Base64(std::vector<uint8_t>(bytes.begin(), bytes.end()));
    };
    b.doc["images"] = Json::array({{{"uri", uri("image/bmp", bmp)}},
                                   {{"uri", uri("image/ktx2", garbage)}},
                                   {{"uri", uri("image/png", garbage)}}});
    b.doc["textures"][0]["extensions"] = {{"KHR_texture_basisu", {{"source", 1}}}};
    b.doc["extensionsUsed"] = Json::array({"KHR_lights_punctual", "KHR_texture_basisu"});
    const LoadedScene loaded = LoadSceneFile(Save("basisu.gltf", b.GltfText()));
    ASSERT_EQ(loaded.scene.textures.size(), 1u);
    const uint32_t texel = loaded.scene.texels[loaded.scene.textures[0].texelOffset];
    EXPECT_EQ(texel & 0xffu, 200u);  // the BMP's red: the core source was sampled
}

TEST_F(GltfTest, MatrixNodesAreDecomposed) {
    GltfBuilder b = test::TwoLevels();
    // The parent as a matrix: columns of a 90-degree turn about y, translation (1, 0, 0).
    b.doc["nodes"][0].erase("translation");
    b.doc["nodes"][0].erase("rotation");
    b.doc["nodes"][0]["matrix"] = {0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
    const LoadedScene loaded = LoadSceneFile(Save("matrix.gltf", b.GltfText()));
    const vec3 p = loaded.scene.instances[0].ObjectToWorld().Point(vec3(1, 0, 0));
    EXPECT_NEAR(glm::length(p - vec3(3, 0, -2)), 0.0f, 1e-5f);
}

// The child's translation animated: LINEAR from (0, 0, 2) at t = 0 to (0, 4, 2) at t = 2; the
// parent's scale STEP 1 until t = 1, then 3.
TEST_F(GltfTest, AnimationIsSampledAtKnownTimes) {
    GltfBuilder b = test::TwoLevels();
    const int times = b.Floats({0, 2}, "SCALAR", 1);
    const int moves = b.Floats({0, 0, 2, 0, 4, 2}, "VEC3", 3);
    const int stepTimes = b.Floats({0, 1}, "SCALAR", 1);
    const int scales = b.Floats({1, 1, 1, 3, 3, 3}, "VEC3", 3);
    b.doc["animations"] =
        Json::array({{{"samplers",
                       {{{"input", times}, {"output", moves}, {"interpolation", "LINEAR"}},
                        {{"input", stepTimes}, {"output", scales}, {"interpolation", "STEP"}}}},
                      {"channels",
                       {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}},
                        {{"sampler", 1}, {"target", {{"node", 0}, {"path", "scale"}}}}}}}});
    const LoadedScene loaded = LoadSceneFile(Save("anim.glb", b.Glb()));
    EXPECT_TRUE(loaded.dynamic);
    ASSERT_EQ(loaded.gltfFiles.size(), 1u);
    EXPECT_EQ(loaded.gltfFiles[0].animatedNodes, 2u);
    EXPECT_FLOAT_EQ(loaded.gltfFiles[0].animationSeconds, 2.0f);
    World world(loaded);
    auto pointAt = [&](float dt) {
        world.Advance(dt);
        return world.Scene().instances[0].ObjectToWorld().Point(vec3(0, 0, 0));
    };
    // t = 0.5: child at (0, 1, 2), parent scale 1: rotated to (2, 1, 0), moved to (3, 1, 0).
    EXPECT_NEAR(glm::length(pointAt(0.5f) - vec3(3, 1, 0)), 0.0f, 1e-4f);
    // t = 1.5: child at (0, 3, 2), parent scale 3: (0, 9, 6) rotated (6, 9, 0), moved (7, 9, 0).
    EXPECT_NEAR(glm::length(pointAt(1.0f) - vec3(7, 9, 0)), 0.0f, 1e-4f);
    // t = 2.5 loops to 0.5.
    EXPECT_NEAR(glm::length(pointAt(1.0f) - vec3(3, 1, 0)), 0.0f, 1e-4f);
}

// A matrix with a zero scale is taken as TRS with that scale (it had been refused as singular,
// while "scale": [0, 0, 0] was not): the axes left keep their directions.
TEST_F(GltfTest, AMatrixWithAZeroScaleIsItsTrs) {
    GltfBuilder b = test::TwoLevels();
    b.doc["nodes"][1].erase("translation");
    b.doc["nodes"][1].erase("scale");
    // Scale (2, 0, 1), rotation x -> y, y -> z, z -> x, translation (0, 0, 2).
    const std::vector<float> m = {0, 2, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 2, 1};
    b.doc["nodes"][1]["matrix"] = m;
    const LoadedScene loaded = LoadSceneFile(Save("flat.gltf", b.GltfText()));
    const glm::mat4 local = physics::ToMatrix(loaded.entities.at(1).local);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(local[c][r], m[size_t(c * 4 + r)], 1e-6f) << "column " << c << " row " << r;
    b.doc["nodes"][1]["matrix"] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 5, 0, 0, 1};
    const LoadedScene hidden = LoadSceneFile(Save("hidden.gltf", b.GltfText()));
    EXPECT_EQ(hidden.entities.at(1).local.scale, vec3(0.0f));
    EXPECT_EQ(hidden.entities.at(1).local.translation, vec3(5, 0, 0));
}

// Keys at time 0 only are a pose (how exporters write one): the node takes it, at the start
// and after. The channel had been dropped, leaving the node at rest.
TEST_F(GltfTest, AChannelOfOneKeyPosesItsNode) {
    GltfBuilder b = test::TwoLevels();
    const int time = b.Floats({0}, "SCALAR", 1);
    const int move = b.Floats({0, 4, 2}, "VEC3", 3);
    b.doc["animations"] = Json::array(
        {{{"samplers", {{{"input", time}, {"output", move}}}},
          {"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}}}}}});
    const LoadedScene loaded = LoadSceneFile(Save("pose.gltf", b.GltfText()));
    World world(loaded);
    // The child at (0, 4, 2) under the parent: rotated to (2, 4, 0), moved to (3, 4, 0).
    const vec3 expected(3, 4, 0);
    EXPECT_NEAR(glm::length(world.Scene().instances[0].ObjectToWorld().Point(vec3(0)) - expected),
                0.0f, 1e-4f);
    world.Advance(0.75f);
    EXPECT_NEAR(glm::length(world.Scene().instances[0].ObjectToWorld().Point(vec3(0)) - expected),
                0.0f, 1e-4f);
}

// A camera whose node an animation moves starts where the animation's first pose has it, as
// the meshes do: (0, 0, 7) under the parent is world (8, 0, 0), not its node's rest (6, 0, 0).
TEST_F(GltfTest, ACameraStartsAtItsAnimationsFirstPose) {
    GltfBuilder b = test::TwoLevels();
    b.doc["cameras"] =
        Json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}});
    const int camera = b.Node({{"camera", 0}, {"translation", {0, 0, 5}}});
    b.doc["nodes"][0]["children"].push_back(camera);
    const int times = b.Floats({0, 1}, "SCALAR", 1);
    const int moves = b.Floats({0, 0, 7, 0, 0, 9}, "VEC3", 3);
    b.doc["animations"] = Json::array(
        {{{"samplers", {{{"input", times}, {"output", moves}}}},
          {"channels",
           {{{"sampler", 0}, {"target", {{"node", camera}, {"path", "translation"}}}}}}}});
    const LoadedScene loaded = LoadSceneFile(Save("moving_camera.gltf", b.GltfText()));
    EXPECT_NEAR(glm::length(loaded.scene.camera.position - vec3(8, 0, 0)), 0.0f, 1e-5f);
}

TEST_F(GltfTest, LightsAndCameraSitOnTheirNodes) {
    GltfBuilder b = test::TwoLevels();
    b.doc["cameras"] =
        Json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}});
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
        Json::array({{{"type", "point"}, {"color", {1, 0.5, 0.25}}, {"intensity", 2}},
                     {{"type", "directional"}},
                     {{"type", "spot"},
                      {"intensity", 100},
                      {"range", 10},
                      {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}}});
    // A camera as a child of the rotated parent, 5 units along its +z: world (1 + 5, 0, 0),
    // looking along the parent's -z turned, i.e. world -x.
    b.doc["nodes"][0]["children"].push_back(b.Node({{"camera", 0}, {"translation", {0, 0, 5}}}));
    b.doc["nodes"][0]["children"].push_back(b.Node(
        {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"translation", {0, 3, 0}}}));
    b.doc["nodes"][0]["children"].push_back(
        b.Node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}}));
    b.doc["nodes"][0]["children"].push_back(
        b.Node({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}}));
    const LoadedScene loaded = LoadSceneFile(Save("lights.gltf", b.GltfText()));
    const Camera& c = loaded.scene.camera;
    EXPECT_NEAR(glm::length(c.position - vec3(6, 0, 0)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(glm::normalize(c.forward) - vec3(-1, 0, 0)), 0.0f, 1e-5f);
    EXPECT_NEAR(c.fovYDegrees, 0.5f * 180.0f / float(M_PI), 1e-4f);
    ASSERT_EQ(loaded.scene.lights.size(), 3u);
    EXPECT_EQ(loaded.scene.lights[0].type, LightType::kPoint);
    EXPECT_NEAR(glm::length(loaded.scene.lights[0].vector - vec3(1, 3, 0)), 0.0f, 1e-5f);
    // candela over pi: what a white surface one unit away shows.
    EXPECT_NEAR(glm::length(loaded.scene.lights[0].color - vec3(2, 1, 0.5f) / kPi), 0.0f, 1e-6f);
    EXPECT_EQ(loaded.scene.lights[0].falloff, 1u);  // inverse-square, no range
    EXPECT_EQ(loaded.scene.lights[0].range, 0.0f);
    // The directional light shines along the parent's -z (world -x): toward it is +x.
    EXPECT_EQ(loaded.scene.lights[1].type, LightType::kDirectional);
    EXPECT_NEAR(glm::length(loaded.scene.lights[1].vector - vec3(1, 0, 0)), 0.0f, 1e-5f);
    EXPECT_EQ(loaded.scene.lights[1].falloff, 0u);
    // The spot sits at the parent's origin (1, 0, 0) and shines along world -x; its cone's
    // weight is 1 at the inner angle and 0 at the outer.
    const Light& spot = loaded.scene.lights[2];
    EXPECT_EQ(spot.type, LightType::kSpot);
    EXPECT_EQ(spot.range, 10.0f);
    EXPECT_NEAR(spot.color.x, 100.0f / kPi, 1e-5f);
    EXPECT_NEAR(glm::length(spot.spotAxis - vec3(-1, 0, 0)), 0.0f, 1e-5f);
    EXPECT_NEAR(std::cos(0.25f) * spot.spotScale + spot.spotOffset, 1.0f, 1e-5f);
    EXPECT_NEAR(std::cos(0.5f) * spot.spotScale + spot.spotOffset, 0.0f, 1e-5f);
}

// Primitives that name the same accessors share one BLAS, whatever their meshes and materials
// (600 primitives of one accessor had built 600 trees); the summary still counts each.
TEST_F(GltfTest, PrimitivesOfTheSameAccessorsShareABlas) {
    GltfBuilder b = test::TwoLevels();
    Json prim = b.doc["meshes"][0]["primitives"][0];
    b.doc["materials"] = Json::array({Json::object(), {{"doubleSided", true}}});
    Json other = prim;
    other["material"] = 1;
    b.doc["meshes"][0]["primitives"] = Json::array({prim, other});
    b.doc["meshes"].push_back({{"primitives", Json::array({prim})}});
    b.doc["nodes"].push_back({{"mesh", 1}});
    b.doc["scenes"][0]["nodes"].push_back(2);
    const LoadedScene loaded = LoadSceneFile(Save("shared.gltf", b.GltfText()));
    EXPECT_EQ(loaded.scene.blases.size(), 1u);
    ASSERT_EQ(loaded.scene.instances.size(), 3u);
    EXPECT_NE(loaded.scene.instances[0].materialId, loaded.scene.instances[1].materialId);
    ASSERT_EQ(loaded.gltfFiles.size(), 1u);
    EXPECT_EQ(loaded.gltfFiles[0].primitives, 3u);
    EXPECT_EQ(loaded.gltfFiles[0].triangles, 3u);
}

// A primitive shown under a skin is read whole wherever an unskinned node showed it first: its
// skin attributes are checked whatever the nodes' order (a shared BLAS had skipped the check).
TEST_F(GltfTest, ASkinnedUseOfASharedPrimitiveIsCheckedInAnyNodeOrder) {
    for (const bool unskinnedFirst : {true, false}) {
        GltfBuilder b;
        const int mesh = b.Mesh(b.Floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3));
        b.doc["meshes"][size_t(mesh)]["primitives"][0]["attributes"]["WEIGHTS_0"] =
            b.Floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 4);
        const Json plain = {{"mesh", mesh}};
        const Json skinned = {{"mesh", mesh}, {"skin", 0}};
        b.Node(unskinnedFirst ? plain : skinned);
        b.Node(unskinnedFirst ? skinned : plain);
        const int joint = b.Node(Json::object());
        b.doc["skins"] = Json::array({{{"joints", {joint}}}});
        b.doc["scenes"] = Json::array({{{"nodes", {0, 1, joint}}}});
        try {
            LoadSceneFile(Save("skin_order.gltf", b.GltfText()));
            ADD_FAILURE() << "loaded, unskinned first: " << unskinnedFirst;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("WEIGHTS_0: given without JOINTS_0"),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST_F(GltfTest, SceneFilePlacesAGltfModelPerInstance) {
    Save("tree.glb", test::TwoLevels().Glb());
    const std::string scene = R"({
        "models": { "tree": { "type": "gltf", "file": "tree.glb" } },
        "instances": [ { "model": "tree" }, { "model": "tree", "position": [0, 10, 0] } ]
    })";
    const LoadedScene loaded = ParseScene(scene, "scene.json", dir_.string());
    ASSERT_EQ(loaded.scene.blases.size(), 1u);  // loaded once, placed twice
    ASSERT_EQ(loaded.scene.instances.size(), 2u);
    const vec3 p = loaded.scene.instances[1].ObjectToWorld().Point(vec3(1, 0, 0));
    EXPECT_NEAR(glm::length(p - vec3(3, 10, -2)), 0.0f, 1e-5f);
    EXPECT_THROW(ParseScene(R"({"models": {"t": {"type": "gltf", "file": "tree.glb"}},
                               "instances": [{"model": "t", "material": "x"}]})",
                            "scene.json", dir_.string()),
                 InputError);
}

// Debian's assimp-testmodels: third-party files, never committed.
std::string AssimpModel(const std::string& name) {
    const std::string path = "/usr/share/assimp/models/glTF2/" + name;
    return fs::exists(path) ? path : "";
}

TEST(GltfAssimpModels, BoxTexturedIsTexturedOnEveryContainer) {
    for (const char* name :
         {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb",
          "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
        const std::string path = AssimpModel(name);
        if (path.empty())
            GTEST_SKIP()
                << "assimp-testmodels is not installed (apt-get install assimp-testmodels)";
        const LoadedScene loaded = LoadSceneFile(path);
        EXPECT_EQ(loaded.scene.TriangleCount(), 12u) << name;
        ASSERT_EQ(loaded.scene.textures.size(), 1u) << name;
        EXPECT_EQ(loaded.scene.textures[0].width, 211u) << name;
        EXPECT_NE(loaded.scene.Features() & kFeatureTextures, 0u) << name;
        EXPECT_FALSE(loaded.scene.blases[0]->uvs.empty()) << name;
    }
}

// The package's primitive-mode files: its strips and fans (modes 5 and 6, with and without
// indices) draw the same quad as its triangle lists, pixel for pixel; points and lines are
// skipped with a warning, leaving nothing to render.
TEST(GltfAssimpModels, StripAndFanFilesDrawTheirTriangleListsQuad) {
    const std::string dir = "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_";
    if (AssimpModel(dir + "06.gltf").empty()) GTEST_SKIP() << "assimp-testmodels is not installed";
    RenderSettings settings;
    settings.width = settings.height = 24;
    settings.maxDepth = 1;
    auto render = [&](const char* number) {
        const LoadedScene loaded = LoadSceneFile(AssimpModel(dir + number + ".gltf"));
        EXPECT_EQ(loaded.scene.TriangleCount(), 2u) << number;
        return RenderRaw(loaded.scene, settings);
    };
    const Image list = render("06");
    // The quad covers a good part of the view: pixels other than the corner's background.
    size_t covered = 0;
    for (const vec3& p : list.pixels) covered += p != list.At(0, 0);
    EXPECT_GT(covered, list.pixels.size() / 4);
    for (const char* number : {"04", "05", "11", "12", "13"}) {
        const Image image = render(number);
        EXPECT_EQ(image.pixels, list.pixels) << number;
    }
    for (const char* number : {"00", "01", "02", "03", "07", "08", "09", "10"}) {
        ::testing::internal::CaptureStderr();
        EXPECT_THROW(LoadSceneFile(AssimpModel(dir + number + ".gltf")), InputError) << number;
        EXPECT_NE(::testing::internal::GetCapturedStderr().find("no surface to trace"),
                  std::string::npos)
            << number;
    }
}

TEST(GltfAssimpModels, MorphCubeLoadsItsTargetsWithoutWarnings) {
    const std::string path =
        AssimpModel("glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
    if (path.empty()) GTEST_SKIP() << "assimp-testmodels is not installed";
    ::testing::internal::CaptureStderr();
    const LoadedScene loaded = LoadSceneFile(path);
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_GT(loaded.scene.TriangleCount(), 0u);
    EXPECT_EQ(warnings, "");
    ASSERT_EQ(loaded.scene.deformableMeshes.size(), 1u);
    EXPECT_EQ(loaded.scene.deformableMeshes[0]->targetCount, 2u);
    EXPECT_FALSE(loaded.scene.deformableMeshes[0]->Skinned());
}

TEST(GltfAssimpModels, RejectedFilesGiveErrors) {
    for (const char* name : {"RecursiveNodes/RecursiveNodes.gltf", "MissingBin/BoxTextured.gltf",
                             "IndexOutOfRange/IndexOutOfRange.gltf",
                             "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb"}) {
        const std::string path = AssimpModel(name);
        if (path.empty()) GTEST_SKIP() << "assimp-testmodels is not installed";
        EXPECT_THROW(LoadSceneFile(path), InputError) << name;
    }
}

}  // namespace
}  // namespace rtrt
