// A glTF file placed by a scene file: grid copies that play the spawner's animation each at their
// own place, and the file's camera and lights placed where the instance starts (its animation's
// first pose), whether an instance or a spawner places it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>

#include "tests/gltf/gltf_test_dir.h"

namespace rtrt {
namespace {

using test::GltfBuilder;
using Json = nlohmann::json;

class GltfPlacementTest : public GltfTest {
  protected:
    // test::TwoLevels with a camera 5 along its rotated parent's +z and a point light above it.
    void SaveModel() const {
        GltfBuilder b = test::TwoLevels();
        b.doc["cameras"] = Json::array(
            {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}});
        b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
            Json::array({{{"type", "point"}, {"intensity", 2}}});
        b.doc["nodes"][0]["children"].push_back(
            b.Node({{"camera", 0}, {"translation", {0, 0, 5}}}));
        b.doc["nodes"][0]["children"].push_back(
            b.Node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
                    {"translation", {0, 3, 0}}}));
        Save("m.gltf", b.GltfText());
    }
    LoadedScene LoadScene(const Json& placements) const {
        SaveModel();
        Json scene = {{"models", {{"m", {{"type", "gltf"}, {"file", "m.gltf"}}}}},
                      {"instances", Json::array()}};
        scene.update(placements);
        std::ofstream(dir_ / "scene.json") << scene.dump();
        return LoadSceneFile((dir_ / "scene.json").string());
    }
};

std::vector<vec3> SpawnedRoots(const LoadedScene& loaded) {
    std::vector<vec3> roots;
    for (const EntityDesc& e : loaded.entities)
        if (e.parent < 0 && std::strcmp(e.sourceArray, "spawners") == 0)
            roots.push_back(e.local.translation);
    std::sort(roots.begin(), roots.end(), [](vec3 a, vec3 b) { return a.x < b.x; });
    return roots;
}

// Each copy of a 3 x 1 x 1 grid, spacing 3, starts at its place: keys and an orbit are moved by
// the place's offset from the spawner's position (all three had stood at the keys' own place).
TEST_F(GltfPlacementTest, GridCopiesPlayTheSpawnersAnimationAtTheirOwnPlaces) {
    for (const Json& animate :
         {Json::parse(R"({"keyframes": {"translation": [[0, 0, 0, 0], [10, 0, 0, -5]]}})"),
          Json::parse(R"({"orbit": {"radius": 1, "period": 4}})")}) {
        const Json spawner = {{"model", "m"},
                              {"grid", {{"count", {3, 1, 1}}, {"spacing", 3}}},
                              {"position", {0, 0, 0}},
                              {"animate", animate}};
        const std::vector<vec3> roots =
            SpawnedRoots(LoadScene({{"spawners", Json::array({spawner})}}));
        ASSERT_EQ(roots.size(), 3u) << animate;
        EXPECT_NEAR(glm::length(roots[1] - roots[0] - vec3(3, 0, 0)), 0.0f, 1e-5f) << animate;
        EXPECT_NEAR(glm::length(roots[2] - roots[1] - vec3(3, 0, 0)), 0.0f, 1e-5f) << animate;
    }
}

// An instance whose keys hold it at z = -15 from the start shows the file's camera and light
// where an instance placed at z = -15 shows them (they were placed from its position, 0).
TEST_F(GltfPlacementTest, CameraAndLightsStartWhereTheInstanceStarts) {
    const LoadedScene still =
        LoadScene({{"instances", Json::array({{{"model", "m"}, {"position", {0, 0, -15}}}})}});
    EXPECT_NEAR(glm::length(still.scene.camera.position - vec3(6, 0, -15)), 0.0f, 1e-5f);
    ASSERT_EQ(still.scene.lights.size(), 1u);
    const Json keys = Json::parse(R"({"keyframes": {"translation": [[0, 0, 0, -15],
                                                                     [1, 0, 0, -15]]}})");
    const LoadedScene animated =
        LoadScene({{"instances",
                    Json::array({{{"model", "m"}, {"position", {0, 0, 0}}, {"animate", keys}}})}});
    EXPECT_NEAR(glm::length(animated.scene.camera.position - still.scene.camera.position), 0.0f,
                1e-5f);
    ASSERT_EQ(animated.scene.lights.size(), 1u);
    EXPECT_NEAR(glm::length(animated.scene.lights[0].vector - still.scene.lights[0].vector), 0.0f,
                1e-5f);
    // A grid spawner's first place gives the camera as an instance there does.
    const LoadedScene grid =
        LoadScene({{"spawners", Json::array({{{"model", "m"},
                                              {"grid", {{"count", {1, 1, 1}}, {"spacing", 1}}},
                                              {"position", {0, 0, -15}}}})}});
    EXPECT_NEAR(glm::length(grid.scene.camera.position - still.scene.camera.position), 0.0f, 1e-5f);
}

}  // namespace
}  // namespace rtrt
