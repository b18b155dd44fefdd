// glTF skins and morph targets, end to end through the World: a skinned two-bone cylinder built
// here (joints and weights in each component type the spec allows) bent at known angles against
// the closed form, its knee driven by a CUBICSPLINE channel at a time with a known answer;
// morph targets at known weights, animated by a weights channel, two instances of one file in
// their own phases; malformed skins and morphs named by field; Debian's assimp-testmodels
// (skipped when the package is missing).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.h"
#include "game/gltf/gltf_import.h"
#include "game/runtime/world.h"
#include "game/scene/scene_file.h"
#include "tests/gltf/gltf_builder.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;
using test::GltfBuilder;
using Json = nlohmann::json;

constexpr int kUByte = 5121, kUShort = 5123;

class GltfDeformTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("rtrt_gltf_deform_" + std::to_string(getpid()) + "_" + info->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string Save(const std::string& name, const std::string& bytes) const {
        const std::string path = (dir_ / name).string();
        GltfBuilder::Save(path, bytes);
        return path;
    }
    fs::path dir_;
};

// The deformed position of rest vertex v of deformation d, in the mesh's own space: linear blend
// skinning by the record's joint matrices, after its morph (what the frame renderer computes).
vec3 Deformed(const RenderScene& scene, const Deformation& d, uint32_t v) {
    const DeformableMesh& mesh = *scene.deformableMeshes[d.mesh];
    vec3 p = mesh.rest.positions[v];
    for (uint32_t t = 0; t < mesh.targetCount; ++t)
        p += d.morphWeights[t] * mesh.positionDeltas[size_t(t) * mesh.VertexCount() + v];
    if (!mesh.Skinned()) return p;
    vec3 skinned(0.0f);
    for (uint32_t i = 0; i < mesh.influences; ++i) {
        const size_t slot = size_t(v) * mesh.influences + i;
        skinned += mesh.weights[slot] * d.jointMatrices[mesh.joints[slot]].Point(p);
    }
    return skinned;
}

// A cylinder of radius 0.25 along +y, rings at y = 0, 0.5, 1, 1.5, 2 of 6 vertices: the thigh
// (y < 1) follows the hip alone, the shin (y > 1) the knee alone, the knee ring half each.
// Joints as unsigned bytes and weights as normalised unsigned bytes, or joints as unsigned
// shorts and weights as floats that do not sum to 1 (the importer normalises them).
// Nodes: 0 the mesh (moved to x = 5: a skinned mesh's node transform does not move it), 1 the
// hip at z = -3, 2 the knee 1 above it, turned by kneeDegrees about z. Bind pose: straight.
GltfBuilder TwoBoneCylinder(float kneeDegrees, bool shortJoints) {
    GltfBuilder b;
    std::vector<float> positions;
    std::vector<uint8_t> joints8, weights8;
    std::vector<uint16_t> joints16;
    std::vector<float> weightsF;
    for (int ring = 0; ring < 5; ++ring)
        for (int step = 0; step < 6; ++step) {
            const float a = float(step) * float(M_PI) / 3.0f, y = 0.5f * float(ring);
            positions.insert(positions.end(), {0.25f * std::cos(a), y, 0.25f * std::sin(a)});
            const int knee = ring == 2, shin = ring > 2;
            const uint16_t j[4] = {uint16_t(shin), uint16_t(knee), 0, 0};
            for (uint16_t x : j) {
                joints8.push_back(uint8_t(x));
                joints16.push_back(x);
            }
            if (knee) {
                weights8.insert(weights8.end(), {128, 128, 0, 0});
                weightsF.insert(weightsF.end(), {3.0f, 3.0f, 0.0f, 0.0f});
            } else {
                weights8.insert(weights8.end(), {255, 0, 0, 0});
                weightsF.insert(weightsF.end(), {2.0f, 0.0f, 0.0f, 0.0f});
            }
        }
    std::vector<uint16_t> indices;
    for (uint16_t ring = 0; ring < 4; ++ring)
        for (uint16_t step = 0; step < 6; ++step) {
            const uint16_t a = ring * 6 + step, b2 = ring * 6 + (step + 1) % 6;
            indices.insert(indices.end(),
                           {a, uint16_t(a + 6), b2, b2, uint16_t(a + 6), uint16_t(b2 + 6)});
        }
    const int pos = b.Floats(positions, "VEC3", 3);
    const int idx = b.Accessor(indices, kUShort, "SCALAR", 1);
    const int joints = shortJoints ? b.Accessor(joints16, kUShort, "VEC4", 4)
                                   : b.Accessor(joints8, kUByte, "VEC4", 4);
    const int weights =
        shortJoints ? b.Floats(weightsF, "VEC4", 4) : b.Accessor(weights8, kUByte, "VEC4", 4);
    if (!shortJoints) b.doc["accessors"][size_t(weights)]["normalized"] = true;
    b.Mesh(pos, idx);
    b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = joints;
    b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = weights;
    // Inverse bind matrices (column-major): translate(0, 0, 3) and translate(0, -1, 3).
    const int ibm = b.Floats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  3, 1,  //
                              1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 3, 1},
                             "MAT4", 16);
    b.doc["skins"] = Json::array({{{"joints", {1, 2}}, {"inverseBindMatrices", ibm}}});
    const float half = glm::radians(kneeDegrees) / 2.0f;
    b.Node({{"mesh", 0}, {"skin", 0}, {"translation", {5, 0, 0}}});
    b.Node({{"children", {2}}, {"translation", {0, 0, -3}}});
    b.Node({{"translation", {0, 1, 0}}, {"rotation", {0, 0, std::sin(half), std::cos(half)}}});
    b.doc["scenes"] = Json::array({{{"nodes", {0, 1}}}});
    return b;
}

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
            World world(LoadSceneFile(Save(file, b.Glb())));
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

// One triangle with normals and two morph targets: target 0 lifts every vertex by z = 1 (and
// tilts normal 0), target 1 moves vertex 0 by x = 1. The weights channel runs LINEAR from
// (0, 0) at t = 0 to (1, 0.5) at t = 2.
GltfBuilder MorphTriangle(bool animated) {
    GltfBuilder b;
    const int pos = b.Floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    const int normal = b.Floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
    const int lift = b.Floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
    const int tilt = b.Floats({1, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3", 3);
    const int shift = b.Floats({1, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3", 3);
    b.Mesh(pos);
    Json& prim = b.doc["meshes"][0]["primitives"][0];
    prim["attributes"]["NORMAL"] = normal;
    prim["targets"] = Json::array({{{"POSITION", lift}, {"NORMAL", tilt}}, {{"POSITION", shift}}});
    b.doc["meshes"][0]["weights"] = {0.5, 0.0};
    b.Node({{"mesh", 0}});
    if (animated) {
        const int times = b.Floats({0, 2}, "SCALAR", 1);
        const int values = b.Floats({0, 0, 1, 0.5f}, "SCALAR", 1);
        b.doc["animations"] = Json::array(
            {{{"samplers", {{{"input", times}, {"output", values}}}},
              {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}}}}});
    }
    return b;
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
    World world(LoadSceneFile(Save("posed_weights.gltf", b.GltfText())));
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
    World world(LoadSceneFile(Save("pointer.gltf", b.GltfText())));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find("1 animation channel(s) without target.node"), std::string::npos)
        << warnings;
    world.Advance(0.5f);
    EXPECT_EQ(Deformed(world.Scene(), world.Scene().deformations.at(0), 0), vec3(1, 0, 0));
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

struct BadDeform {
    const char* name;
    void (*edit)(GltfBuilder&);
    const char* field;
    const char* reason;
};

void SetAttribute(GltfBuilder& b, const char* name, int accessor) {
    b.doc["meshes"][0]["primitives"][0]["attributes"][name] = accessor;
}

TEST_F(GltfDeformTest, MalformedSkinsAndMorphsNameTheirField) {
    const std::string prim = "meshes[0].primitives[0]";
    const BadDeform cases[] = {
        {"joint_out_of_range",
         [](GltfBuilder& b) {
             std::vector<uint8_t> j(30 * 4, 0);
             j[4 * 7] = 9;
             SetAttribute(b, "JOINTS_0", b.Accessor(j, kUByte, "VEC4", 4));
         },
         ".attributes.JOINTS_0", "joint 9 out of range (the skin has 2 joints)"},
        {"float_joints",
         [](GltfBuilder& b) {
             SetAttribute(b, "JOINTS_0", b.Floats(std::vector<float>(120, 0.0f), "VEC4", 4));
         },
         ".attributes.JOINTS_0", "unsigned bytes or unsigned shorts"},
        {"negative_weight",
         [](GltfBuilder& b) {
             std::vector<float> w(120, 0.25f);
             w[5] = -1.0f;
             SetAttribute(b, "WEIGHTS_0", b.Floats(w, "VEC4", 4));
         },
         ".attributes.WEIGHTS_0", "vertex 1: a weight is negative"},
        {"short_weights",
         [](GltfBuilder& b) {
             SetAttribute(b, "WEIGHTS_0", b.Floats(std::vector<float>(40, 0.25f), "VEC4", 4));
         },
         ".attributes.WEIGHTS_0", "10 elements, but POSITION has 30"},
        {"joints_without_weights",
         [](GltfBuilder& b) {
             SetAttribute(b, "JOINTS_1",
                          b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"]);
         },
         ".attributes.JOINTS_1", "given without WEIGHTS_1"},
    };
    for (const BadDeform& c : cases) {
        GltfBuilder b = TwoBoneCylinder(30.0f, false);
        c.edit(b);
        try {
            LoadSceneFile(Save(std::string(c.name) + ".glb", b.Glb()));
            ADD_FAILURE() << c.name << ": loaded without an error";
        } catch (const InputError& e) {
            EXPECT_EQ(e.Field(), prim + c.field) << c.name << ": " << e.what();
            EXPECT_NE(e.Reason().find(c.reason), std::string::npos) << c.name << ": " << e.what();
        }
    }
    const BadDeform others[] = {
        {"skin_joint_out_of_range", [](GltfBuilder& b) { b.doc["skins"][0]["joints"][1] = 7; },
         "skins[0].joints[1]", "node 7 out of range"},
        {"few_inverse_binds",
         [](GltfBuilder& b) {
             b.doc["skins"][0]["inverseBindMatrices"] =
                 b.Floats(std::vector<float>(16, 1.0f), "MAT4", 16);
         },
         "skins[0].inverseBindMatrices", "1 matrices for 2 joints"},
        {"node_skin_out_of_range", [](GltfBuilder& b) { b.doc["nodes"][0]["skin"] = 3; },
         "nodes[0].skin", "skin 3 out of range"},
        {"joint_outside_scene",
         [](GltfBuilder& b) {
             b.Node(Json::object());
             b.doc["skins"][0]["joints"][0] = 3;
         },
         "skins[0].joints[0]", "not in the scene shown"},
        {"joint_twice",
         [](GltfBuilder& b) {
             b.doc["skins"][0]["joints"] = {2, 1, 2};
         },
         "skins[0].joints", "node 2 is listed twice"},
        // Named at the skin, not at the first vertex whose joint it lacks.
        {"no_joints", [](GltfBuilder& b) { b.doc["skins"][0]["joints"] = Json::array(); },
         "skins[0].joints", "a skin needs at least one joint"},
    };
    for (const BadDeform& c : others) {
        GltfBuilder b = TwoBoneCylinder(30.0f, false);
        c.edit(b);
        try {
            LoadSceneFile(Save(std::string(c.name) + ".glb", b.Glb()));
            ADD_FAILURE() << c.name << ": loaded without an error";
        } catch (const InputError& e) {
            EXPECT_EQ(e.Field(), c.field) << c.name << ": " << e.what();
            EXPECT_NE(e.Reason().find(c.reason), std::string::npos) << c.name << ": " << e.what();
        }
    }
    const BadDeform morphs[] = {
        {"mesh_weights_count",
         [](GltfBuilder& b) {
             b.doc["meshes"][0]["weights"] = {1, 2, 3};
         },
         "meshes[0].weights", "3 weights for 2 morph targets"},
        {"node_weights_count", [](GltfBuilder& b) { b.doc["nodes"][0]["weights"] = {1}; },
         "nodes[0].weights", "1 weights for 2 morph targets"},
        {"delta_count",
         [](GltfBuilder& b) {
             b.doc["meshes"][0]["primitives"][0]["targets"][1]["POSITION"] =
                 b.Floats({1, 0, 0}, "VEC3", 3);
         },
         "meshes[0].primitives[0].targets[1].POSITION", "1 deltas, but POSITION has 3"},
        {"weights_output_count",
         [](GltfBuilder& b) {
             b.doc["animations"][0]["samplers"][0]["output"] = b.Floats({0, 1, 0}, "SCALAR", 1);
         },
         "animations[0].samplers[0].output", "3 values for 2 key times of 2 weights"},
        {"cubic_output_count",
         [](GltfBuilder& b) {
             b.doc["animations"][0]["samplers"][0]["interpolation"] = "CUBICSPLINE";
         },
         "animations[0].samplers[0].output", "(CUBICSPLINE"},
        {"same_target_twice",
         [](GltfBuilder& b) {
             b.doc["animations"][0]["channels"].push_back(b.doc["animations"][0]["channels"][0]);
         },
         "animations[0].channels[1].target", "node 0's weights is animated by an earlier channel"},
        {"mesh_weights_without_targets",
         [](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0].erase("targets"); },
         "meshes[0].weights", "2 weights for 0 morph targets"},
    };
    for (const BadDeform& c : morphs) {
        GltfBuilder b = MorphTriangle(true);
        c.edit(b);
        try {
            LoadSceneFile(Save(std::string(c.name) + ".glb", b.Glb()));
            ADD_FAILURE() << c.name << ": loaded without an error";
        } catch (const InputError& e) {
            EXPECT_EQ(e.Field(), c.field) << c.name << ": " << e.what();
            EXPECT_NE(e.Reason().find(c.reason), std::string::npos) << c.name << ": " << e.what();
        }
    }
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
