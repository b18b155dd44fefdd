// Malformed skins and morph targets are refused naming their field: joints and weights of the
// wrong type, count or range, skins whose joints are out of range, outside the scene or listed
// twice, morph weights that do not match the targets, channels that animate one target twice.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/core/error.h"
#include "game/scene/scene_file.h"
#include "tests/gltf/deform_models.h"

namespace rtrt {
namespace {

using test::GltfBuilder;
using test::GltfDeformTest;
using test::kUByte;
using test::MorphTriangle;
using test::TwoBoneCylinder;
using Json = nlohmann::json;

struct BadDeform {
    const char* name;
    void (*edit)(GltfBuilder&);
    const char* field;
    const char* reason;
};

void SetAttribute(GltfBuilder& b, const char* name, int accessor) {
    b.doc["meshes"][0]["primitives"][0]["attributes"][name] = accessor;
}

class GltfDeformErrorTest : public GltfDeformTest {
  protected:
    // Each case's edit of a fresh file from MAKE is refused naming PREFIX + its field.
    template <size_t N, typename Make>
    void ExpectEachRefused(const BadDeform (&list)[N], Make make, const std::string& prefix) {
        for (const BadDeform& c : list) {
            GltfBuilder b = make();
            c.edit(b);
            try {
                LoadSceneFile(Save(std::string(c.name) + ".glb", b.Glb()));
                ADD_FAILURE() << c.name << ": loaded without an error";
            } catch (const InputError& e) {
                EXPECT_EQ(e.Field(), prefix + c.field) << c.name << ": " << e.what();
                EXPECT_NE(e.Reason().find(c.reason), std::string::npos)
                    << c.name << ": " << e.what();
            }
        }
    }
};

TEST_F(GltfDeformErrorTest, MalformedSkinsAndMorphsNameTheirField) {
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
    ExpectEachRefused(
        cases, [] { return TwoBoneCylinder(30.0f, false); }, prim);
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
    ExpectEachRefused(
        others, [] { return TwoBoneCylinder(30.0f, false); }, "");
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
    ExpectEachRefused(
        morphs, [] { return MorphTriangle(true); }, "");
}

}  // namespace
}  // namespace rtrt
