#pragma once
// The glTF files of the deformation tests, built in code: a skinned two-bone cylinder and a
// morphing triangle, with the fixture that saves them and the deformed position of a vertex.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/render_rt/render_scene.h"
#include "tests/gltf/gltf_builder.h"

namespace rtrt::test {

namespace fs = std::filesystem;
using Json = nlohmann::json;

inline constexpr int kUByte = 5121, kUShort = 5123;

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
inline vec3 Deformed(const RenderScene& scene, const Deformation& d, uint32_t v) {
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
inline GltfBuilder TwoBoneCylinder(float kneeDegrees, bool shortJoints) {
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

// One triangle with normals and two morph targets: target 0 lifts every vertex by z = 1 (and
// tilts normal 0), target 1 moves vertex 0 by x = 1. The weights channel runs LINEAR from
// (0, 0) at t = 0 to (1, 0.5) at t = 2.
inline GltfBuilder MorphTriangle(bool animated) {
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

}  // namespace rtrt::test
