// glTF skins and morph targets, end to end through the World: a skinned two-bone cylinder built
// here (joints and weights in each component type the spec allows) bent at known angles against
// the closed form, its knee driven by a CUBICSPLINE channel at a time with a known answer;
// morph targets at known weights, animated by a weights channel, two instances of one file in
// their own phases; Debian's assimp-testmodels (skipped when the package is missing). Malformed
// skins and morphs: gltf_deform_errors_test.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.h"
#include "game/gltf/gltf_import.h"
#include "game/runtime/world.h"
#include "game/scene/scene_file.h"
#include "tests/gltf/deform_models.h"
#include "tests/gltf/gltf_builder.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;
using test::Deformed;
using test::GltfBuilder;
using test::GltfDeformTest;
using test::MorphTriangle;
using test::TwoBoneCylinder;
using Json = nlohmann::json;

// The bind pose is where the vertices are (each inverse bind matrix undoes its joint's bind
// world), so a pose moves world positions by jointWorld * inverse(bind world): the thigh stays,
// the shin turns by theta about z through the knee (0, 1, -3), the knee ring goes half way.
vec3 ExpectedWorld(vec3 p, float theta) {
    if (p.y < 1.0f) return p;
    const vec3 bent(p.x * std::cos(theta) - (p.y - 1.0f) * std::sin(theta),
                    1.0f + p.x * std::sin(theta) + (p.y - 1.0f) * std::cos(theta), p.z);
    return p.y > 1.0f ? bent : 0.5f * (bent + p);
}

void ExpectBentCylinder(const World& world, float theta, const std::string& what) {
    const RenderScene& scene = world.Scene();
    ASSERT_EQ(scene.deformations.size(), 1u) << what;
    ASSERT_EQ(scene.instances.size(), 1u) << what;
    const Deformation& d = scene.deformations[0];
    const DeformableMesh& mesh = *scene.deformableMeshes[d.mesh];
    EXPECT_EQ(mesh.influences, 4u);
    EXPECT_EQ(mesh.jointCount, 2u);
    for (uint32_t v = 0; v < mesh.VertexCount(); ++v) {
        const vec3 rest = mesh.rest.positions[v];
        const vec3 world = scene.instances[0].ObjectToWorld().Point(Deformed(scene, d, v));
        EXPECT_NEAR(glm::length(world - ExpectedWorld(rest, theta)), 0.0f, 1e-5f)
            << what << ": vertex " << v << " at y = " << rest.y;
    }
}

TEST_F(GltfDeformTest, SkinnedTwoBoneCylinderBendsAsTheClosedFormSays) {
    for (bool shortJoints : {false, true})
        for (float degrees : {0.0f, 45.0f, 90.0f, -120.0f}) {
            const std::string name = std::string(shortJoints ? "short" : "byte") + "_" +
                                     std::to_string(int(degrees)) + ".glb";
            ::testing::internal::CaptureStderr();
            const LoadedScene loaded =
                LoadSceneFile(Save(name, TwoBoneCylinder(degrees, shortJoints).Glb()));
            EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << name;
            const DeformableMesh& mesh = *loaded.scene.deformableMeshes.at(0);
            for (uint32_t v = 0; v < mesh.VertexCount(); ++v) {
                float sum = 0.0f;
                for (uint32_t i = 0; i < 4; ++i) sum += mesh.weights[v * 4 + i];
                EXPECT_NEAR(sum, 1.0f, 1e-6f) << name << ": vertex " << v;
            }
            World world(loaded);
            ExpectBentCylinder(world, glm::radians(degrees), name);
            EXPECT_EQ(world.Changes().deformations.size(), 1u);
        }
}

// glTF ignores a skinned mesh node's transform, so one that cannot be inverted (scaled to 0 on one
// axis or all, or by 1e-20, itself or through its parent) poses the mesh as any other: the mesh
// had vanished (its instance placed it by that transform and its joints undid it).
TEST_F(GltfDeformTest, ASkinnedMeshNodeThatCannotBeInvertedIsStillIgnored) {
    const std::vector<std::pair<std::string, Json>> nodes = {
        {"zero", {{"scale", {0, 0, 0}}}},
        {"flat", {{"scale", {1, 0, 1}}}},
        {"tiny", {{"scale", {1e-20, 1e-20, 1e-20}}}},
        {"rotated", {{"rotation", {0, 0.7071068, 0, 0.7071068}}, {"scale", {3, 3, 3}}}}};
    for (const auto& [name, transform] : nodes)
        for (const bool parented : {false, true}) {
            GltfBuilder b = TwoBoneCylinder(90.0f, false);
            Json& mesh = b.doc["nodes"][0];
            if (parented) {
                b.Node({{"children", {0}}});
                b.doc["nodes"][3].update(transform);
                b.doc["scenes"][0]["nodes"] = {3, 1};
            } else {
                mesh.update(transform);
            }
            const std::string file = name + (parented ? "_parent" : "") + ".glb";
            const LoadedScene loaded = LoadSceneFile(Save(file, b.Glb()));
            World world(loaded);
            ExpectBentCylinder(world, glm::radians(90.0f), file);
        }
}

// glTF makes a skin's inverseBindMatrices optional (identity matrices); Debian's tinygltf 2.7
// reports it missing, and such a file was refused. With identities the skin matrices are the
// joints' world transforms: the thigh moves with the hip to z = -3, the shin with the knee one
// further up, the knee ring half way.
TEST_F(GltfDeformTest, ASkinWithoutInverseBindMatricesTakesIdentities) {
    GltfBuilder b = TwoBoneCylinder(0.0f, false);
    b.doc["skins"][0].erase("inverseBindMatrices");
    ::testing::internal::CaptureStderr();
    const LoadedScene loaded = LoadSceneFile(Save("no_inverse_binds.gltf", b.GltfText()));
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    World world(loaded);
    const RenderScene& scene = world.Scene();
    ASSERT_EQ(scene.deformations.size(), 1u);
    const Deformation& d = scene.deformations[0];
    const DeformableMesh& mesh = *scene.deformableMeshes[d.mesh];
    for (uint32_t v = 0; v < mesh.VertexCount(); ++v) {
        const vec3 rest = mesh.rest.positions[v];
        const float up = rest.y < 1.0f ? 0.0f : (rest.y > 1.0f ? 1.0f : 0.5f);
        const vec3 world = scene.instances[0].ObjectToWorld().Point(Deformed(scene, d, v));
        EXPECT_NEAR(glm::length(world - (rest + vec3(0.0f, up, -3.0f))), 0.0f, 1e-5f)
            << "vertex " << v << " at y = " << rest.y;
    }
}

TEST_F(GltfDeformTest, CubicSplineKneeChannelBendsByTheSpecificationsSpline) {
    GltfBuilder b = TwoBoneCylinder(0.0f, false);
    // Keys at 0 and 1 s: identity, then 90 degrees about z; every tangent zero. Each key is
    // in-tangent, value, out-tangent (x, y, z, w).
    const float s = std::sqrt(0.5f);
    const int times = b.Floats({0, 1}, "SCALAR", 1);
    const int output = b.Floats({0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0,  //
                                 0, 0, 0, 0, 0, 0, s, s, 0, 0, 0, 0},
                                "VEC4", 4);
    b.doc["animations"] = Json::array(
        {{{"samplers", {{{"input", times}, {"output", output}, {"interpolation", "CUBICSPLINE"}}}},
          {"channels", {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}}}}}});
    ::testing::internal::CaptureStderr();
    const LoadedScene loaded = LoadSceneFile(Save("cubic.glb", b.Glb()));
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    World world(loaded);
    world.Advance(0.25f);
    // u = 0.25: h00 = 0.84375, h01 = 0.15625; q = (0, 0, 0.15625 s, 0.84375 + 0.15625 s)
    // normalised: a turn of 2 atan2(0.15625 s, 0.84375 + 0.15625 s) = 13.21 degrees (linear
    // interpolation would give 22.5).
    ExpectBentCylinder(world, 2.0f * std::atan2(0.15625f * s, 0.84375f + 0.15625f * s), "t = 0.25");
    EXPECT_EQ(world.Changes().deformations.size(), 1u);
    world.Advance(0.25f);  // u = 0.5: the spline with zero tangents is halfway, 45 degrees
    ExpectBentCylinder(world, glm::radians(45.0f), "t = 0.5");
}

TEST_F(GltfDeformTest, UnweightedVerticesStayInTheirMeshNodesFrame) {
    GltfBuilder b = TwoBoneCylinder(90.0f, true);
    // Vertex 0 (thigh) loses its weight: it follows the mesh node (x = 5), unskinned.
    const int weights = b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"];
    const int view = b.doc["accessors"][size_t(weights)]["bufferView"];
    const size_t offset = b.doc["bufferViews"][size_t(view)]["byteOffset"];
    std::memset(b.bin.data() + offset, 0, 16);
    const LoadedScene loaded = LoadSceneFile(Save("unweighted.glb", b.Glb()));
    const DeformableMesh& mesh = *loaded.scene.deformableMeshes.at(0);
    EXPECT_EQ(mesh.jointCount, 3u);  // the skin's two and the node's own
    World world(loaded);
    const RenderScene& scene = world.Scene();
    const vec3 rest = mesh.rest.positions[0];
    const vec3 p =
        scene.instances[0].ObjectToWorld().Point(Deformed(scene, scene.deformations[0], 0));
    EXPECT_NEAR(glm::length(p - (rest + vec3(5, 0, 0))), 0.0f, 1e-5f);  // the node's frame
    const vec3 shin =
        scene.instances[0].ObjectToWorld().Point(Deformed(scene, scene.deformations[0], 29));
    EXPECT_NEAR(glm::length(shin - ExpectedWorld(mesh.rest.positions[29], glm::radians(90.0f))),
                0.0f, 1e-5f);
}

TEST_F(GltfDeformTest, MorphTargetsAtKnownWeights) {
    const LoadedScene loaded = LoadSceneFile(Save("morph.glb", MorphTriangle(false).Glb()));
    const DeformableMesh& mesh = *loaded.scene.deformableMeshes.at(0);
    EXPECT_EQ(mesh.targetCount, 2u);
    EXPECT_EQ(mesh.defaultWeights, (std::vector<float>{0.5f, 0.0f}));
    ASSERT_EQ(mesh.normalDeltas.size(), 6u);
    EXPECT_EQ(mesh.normalDeltas[0], vec3(1, 0, 0));
    World world(loaded);
    const Deformation& d = world.Scene().deformations.at(0);
    EXPECT_EQ(d.morphWeights, (std::vector<float>{0.5f, 0.0f}));  // mesh.weights
    // (0, 0, 0) + 0.5 (0, 0, 1) + 0 (1, 0, 0) = (0, 0, 0.5).
    EXPECT_EQ(Deformed(world.Scene(), d, 0), vec3(0, 0, 0.5f));
    // The node's weights override the mesh's: (0, 0, 0) + 0.25 (0, 0, 1) + 1 (1, 0, 0).
    GltfBuilder b = MorphTriangle(false);
    b.doc["nodes"][0]["weights"] = {0.25, 1.0};
    const LoadedScene own = LoadSceneFile(Save("node_weights.glb", b.Glb()));
    World ownWorld(own);
    EXPECT_EQ(Deformed(ownWorld.Scene(), ownWorld.Scene().deformations.at(0), 0),
              vec3(1, 0, 0.25f));
}

// An accessor without a buffer view is all zeros (glTF 2.0, 5.1.2): a target that moves no
// normal; it had been refused as "buffer view -1 out of range".
TEST_F(GltfDeformTest, AnAccessorWithoutABufferViewIsZeros) {
    GltfBuilder b = MorphTriangle(false);
    b.doc["accessors"].push_back({{"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
    b.doc["meshes"][0]["primitives"][0]["targets"][1]["NORMAL"] = b.doc["accessors"].size() - 1;
    b.doc["meshes"][0]["primitives"][0]["targets"][0]["NORMAL"] = b.doc["accessors"].size() - 1;
    const LoadedScene loaded = LoadSceneFile(Save("zero_normals.gltf", b.GltfText()));
    const DeformableMesh& mesh = *loaded.scene.deformableMeshes.at(0);
    ASSERT_EQ(mesh.normalDeltas.size(), 6u);
    for (const vec3& delta : mesh.normalDeltas) EXPECT_EQ(delta, vec3(0.0f));
    EXPECT_EQ(mesh.positionDeltas.at(0), vec3(0, 0, 1));
    // A count no buffer could parallel is refused (a 600-byte file had asked for 1.6 GB).
    b.doc["accessors"].back()["count"] = 30000000;
    try {
        LoadSceneFile(Save("many_zeros.gltf", b.GltfText()));
        ADD_FAILURE() << "30,000,000 zero normals were taken";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("30000000 elements without a buffer view"),
                  std::string::npos)
            << e.what();
    }
}

// A weights channel of one key sets the node's weights for good; it had been dropped.
TEST_F(GltfDeformTest, AWeightsChannelOfOneKeyIsTheNodesWeights) {
    GltfBuilder b = MorphTriangle(false);
    const int times = b.Floats({0}, "SCALAR", 1);
    const int values = b.Floats({0.0f, 1.0f}, "SCALAR", 1);
    b.doc["animations"] = Json::array(
        {{{"samplers", {{{"input", times}, {"output", values}}}},
          {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}}}}});
    const LoadedScene loaded = LoadSceneFile(Save("posed_weights.gltf", b.GltfText()));
    World world(loaded);
    world.Advance(0.5f);
    // (0, 0, 0) + 0 (0, 0, 1) + 1 (1, 0, 0).
    EXPECT_EQ(Deformed(world.Scene(), world.Scene().deformations.at(0), 0), vec3(1, 0, 0));
}

// A channel may leave target.node to an extension (KHR_animation_pointer): it is skipped with a
// warning and the others play (the file had been refused with tinygltf's raw message).
TEST_F(GltfDeformTest, AChannelWithoutATargetNodeIsSkipped) {
    GltfBuilder b = MorphTriangle(false);
    const int times = b.Floats({0}, "SCALAR", 1);
    const int values = b.Floats({0.0f, 1.0f}, "SCALAR", 1);
    b.doc["animations"] = Json::array(
        {{{"samplers", {{{"input", times}, {"output", values}}}},
          {"channels",
           {{{"sampler", 0},
             {"target",
              {{"path", "pointer"},
               {"extensions", {{"KHR_animation_pointer", {{"pointer", "/nodes/0/weights"}}}}}}}},
            {{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}}}}});
    ::testing::internal::CaptureStderr();
    const LoadedScene loaded = LoadSceneFile(Save("pointer.gltf", b.GltfText()));
    World world(loaded);
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find("1 animation channel(s) without target.node"), std::string::npos)
        << warnings;
    world.Advance(0.5f);
    EXPECT_EQ(Deformed(world.Scene(), world.Scene().deformations.at(0), 0), vec3(1, 0, 0));
    // Messages name the file's channel, counting the skipped one.
    b.doc["animations"][0]["channels"][1]["sampler"] = 5;
    try {
        LoadSceneFile(Save("pointer_bad.gltf", b.GltfText()));
        ADD_FAILURE() << "sampler 5 was taken";
    } catch (const InputError& e) {
        EXPECT_EQ(e.Field(), "animations[0].channels[1].sampler") << e.what();
    }
}

// A skin only another scene of the file uses does not fail the scene shown ("node 1 is not in
// the scene shown").
TEST_F(GltfDeformTest, ASkinOfAnotherSceneDoesNotFailTheSceneShown) {
    GltfBuilder b = TwoBoneCylinder(0.0f, false);
    const int triangle = b.Floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    b.Mesh(triangle);
    const int plain = b.Node({{"mesh", 1}});
    b.doc["scenes"] = Json::array({{{"nodes", {plain}}}, {{"nodes", {0, 1}}}});
    b.doc["scene"] = 0;
    const LoadedScene loaded = LoadSceneFile(Save("other_scene_skin.gltf", b.GltfText()));
    EXPECT_TRUE(loaded.scene.deformableMeshes.empty());
    // The skin's fields are still checked.
    b.doc["skins"][0]["joints"] = {1, 9};
    EXPECT_THROW(LoadSceneFile(Save("bad_other_skin.gltf", b.GltfText())), InputError);
}

// The camera rtrt frames a file without one with looks at the skinned cylinder (around
// (0, 1, 0)), not at its mesh node's x = 5, which does not place a skinned mesh.
TEST_F(GltfDeformTest, TheFramingCameraLooksAtASkinnedMeshNotItsNode) {
    const LoadedScene loaded =
        LoadSceneFile(Save("framed.gltf", TwoBoneCylinder(0.0f, false).GltfText()));
    const Camera& c = loaded.scene.camera;
    const vec3 toCentre = vec3(0, 1, 0) - c.position;
    EXPECT_NEAR(glm::length(glm::cross(toCentre, glm::normalize(c.forward))), 0.0f, 1e-4f);
    EXPECT_LT(glm::length(toCentre), 10.0f);  // framed to the cylinder's size (2 tall)
}

TEST_F(GltfDeformTest, WeightsChannelAnimatesEachInstanceInItsOwnPhase) {
    Save("morph.glb", MorphTriangle(true).Glb());
    const LoadedScene loaded = ParseScene(R"({
        "models": { "m": { "type": "gltf", "file": "morph.glb" } },
        "instances": [ { "model": "m" }, { "model": "m", "position": [3, 0, 0], "phase": 1 } ]
    })",
                                          "scene.json", dir_.string());
    World world(loaded);
    const RenderScene& scene = world.Scene();
    ASSERT_EQ(scene.deformations.size(), 2u);
    EXPECT_NE(scene.deformations[0].blasId, scene.deformations[1].blasId);
    EXPECT_EQ(scene.deformations[0].morphWeights, (std::vector<float>{0.0f, 0.0f}));
    EXPECT_EQ(scene.deformations[1].morphWeights, (std::vector<float>{0.5f, 0.25f}));
    world.Advance(0.5f);
    EXPECT_EQ(scene.deformations[0].morphWeights, (std::vector<float>{0.25f, 0.125f}));
    EXPECT_EQ(scene.deformations[1].morphWeights, (std::vector<float>{0.75f, 0.375f}));
    EXPECT_EQ(world.Changes().deformations.size(), 2u);
    // (0, 0, 0) + 0.75 (0, 0, 1) + 0.375 (1, 0, 0).
    EXPECT_EQ(Deformed(scene, scene.deformations[1], 0), vec3(0.375f, 0, 0.75f));
    // A paused frame changes no weights and hands on no deformation.
    world.Advance(0.0f);
    EXPECT_TRUE(world.Changes().deformations.empty());
}

// A grid spawner of a glTF scene: one deforming instance per place, each in a phase of its own
// (phase + phase_spread x frac(k x golden ratio)), each with its own Deformation.
TEST_F(GltfDeformTest, GridSpawnerPlacesEachCopyInItsOwnPhase) {
    Save("morph.glb", MorphTriangle(true).Glb());
    const LoadedScene loaded = ParseScene(R"({
        "models": { "m": { "type": "gltf", "file": "morph.glb" } },
        "instances": [],
        "spawners": [ { "model": "m", "grid": { "count": [3, 1, 1], "spacing": 2 },
                        "phase": 0.5, "phase_spread": 1 } ]
    })",
                                          "scene.json", dir_.string());
    World world(loaded);
    const RenderScene& scene = world.Scene();
    ASSERT_EQ(scene.deformations.size(), 3u);
    // Phases 0.5, 0.5 + 0.618..., 0.5 + 0.236...: weights 0.5 x phase (the channel above).
    const float phases[3] = {0.5f, 0.5f + 0.6180340f, 0.5f + 0.2360680f};
    for (uint32_t k = 0; k < 3; ++k) {
        SCOPED_TRACE("copy " + std::to_string(k));
        ASSERT_EQ(scene.deformations[k].morphWeights.size(), 2u);
        EXPECT_NEAR(scene.deformations[k].morphWeights[0], 0.5f * phases[k], 1e-5f);
    }
}

TEST_F(GltfDeformTest, GridSpawnerOfAGltfSceneRefusesRainAndLaterTimes) {
    Save("morph.glb", MorphTriangle(true).Glb());
    auto load = [&](const std::string& spawner) {
        ParseScene(R"({ "models": { "m": { "type": "gltf", "file": "morph.glb" } },
                        "instances": [], "spawners": [ )" +
                       spawner + " ] }",
                   "scene.json", dir_.string());
    };
    EXPECT_THROW(load(R"({ "model": "m", "grid": { "count": [2, 1, 1] }, "time": 1 })"),
                 InputError);
    EXPECT_THROW(load(R"({ "model": "m" })"), InputError);
    // Phases are bounded as the scene's other times (at 1e20 the animation clock stood still).
    EXPECT_THROW(load(R"({ "model": "m", "grid": { "count": [1, 1, 1] }, "phase": 1e20 })"),
                 InputError);
    EXPECT_THROW(load(R"({ "model": "m", "grid": { "count": [1, 1, 1] }, "phase": -2e6 })"),
                 InputError);
    EXPECT_THROW(ParseScene(R"({ "models": { "m": { "type": "gltf", "file": "morph.glb" } },
                                 "instances": [ { "model": "m", "phase": 1e20 } ] })",
                            "scene.json", dir_.string()),
                 InputError);
}

// Debian's assimp-testmodels: third-party files, never committed.
std::string AssimpModel(const std::string& name) {
    const std::string path = "/usr/share/assimp/models/glTF2/" + name;
    return fs::exists(path) ? path : "";
}

TEST(GltfDeformAssimpModels, SimpleSkinBendsOverItsAnimation) {
    const std::string path = AssimpModel("simple_skin/simple_skin.gltf");
    if (path.empty()) GTEST_SKIP() << "assimp-testmodels is not installed";
    const LoadedScene loaded = LoadSceneFile(path);
    ASSERT_EQ(loaded.scene.deformableMeshes.size(), 1u);
    EXPECT_TRUE(loaded.scene.deformableMeshes[0]->Skinned());
    World world(loaded);
    const RenderScene& scene = world.Scene();
    ASSERT_EQ(scene.deformations.size(), 1u);
    const vec3 top = Deformed(scene, scene.deformations[0], 9);
    world.Advance(1.0f);
    EXPECT_EQ(world.Changes().deformations.size(), 1u);
    EXPECT_GT(glm::length(Deformed(scene, scene.deformations[0], 9) - top), 0.01f);
}

TEST(GltfDeformAssimpModels, AnimatedMorphCubeChangesItsWeights) {
    const std::string path =
        AssimpModel("glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
    if (path.empty()) GTEST_SKIP() << "assimp-testmodels is not installed";
    const LoadedScene loaded = LoadSceneFile(path);
    World world(loaded);
    const std::vector<float> before = world.Scene().deformations.at(0).morphWeights;
    world.Advance(1.0f);
    EXPECT_NE(world.Scene().deformations.at(0).morphWeights, before);
    EXPECT_EQ(world.Changes().deformations.size(), 1u);
}

}  // namespace
}  // namespace rtrt
