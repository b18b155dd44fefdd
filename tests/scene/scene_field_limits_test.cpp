// Scene-file fields at their limits: values that are valid JSON but that rtrt cannot honour are
// refused with the field and the reason, never read as something else.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/error.h"
#include "game/scene/scene_file.h"
#include "tests/scratch_folder.h"

namespace rtrt {
namespace {

// The InputError's field and reason for a scene parsed from JSON in BASEDIR, or "" when none.
std::string Refusal(const std::string& json, const std::string& baseDir = "") {
    try {
        ParseScene(json, "s.json", baseDir);
    } catch (const InputError& e) {
        return e.Field() + ": " + e.Reason();
    }
    return "";
}

// A path with a NUL in it had been opened up to the NUL ("tri.obj\u0000junk" loaded tri.obj).
TEST(SceneFieldLimits, ANameOrPathHoldingANulIsRefused) {
    EXPECT_EQ(Refusal(R"({"models": {"m": {"type": "mesh", "file": "tri.obj\u0000junk"}},
                          "instances": [{"model": "m"}]})"),
              "models.m.file: holds a NUL character (\\u0000), which no name or path can");
    EXPECT_EQ(Refusal(R"({"models": {"m": {"type": "sphere"}},
                          "instances": [{"model": "m\u0000x"}]})"),
              "instances[0].model: holds a NUL character (\\u0000), which no name or path can");
}

// A range of 0 had meant no range at all, while 1e-30 put the light out.
TEST(SceneFieldLimits, ALightsRangeMustBeARange) {
    const std::string light = R"({"lights": [{"type": "point", "position": [0, 0, 5],
        "falloff": "inverse_square", "range": RANGE}], "instances": []})";
    auto with = [&](const std::string& range) {
        std::string s = light;
        return s.replace(s.find("RANGE"), 5, range);
    };
    EXPECT_EQ(Refusal(with("0")), "lights[0].range: must be greater than 0, got 0");
    EXPECT_EQ(Refusal(with("-2")), "lights[0].range: must be greater than 0, got -2");
    EXPECT_EQ(Refusal(with("1e31")), "lights[0].range: must be at most 1e30");
    EXPECT_EQ(Refusal(with("25")), "");
    EXPECT_EQ(ParseScene(with("25"), "s.json", "").scene.lights[0].range, 25.0f);
}

// A plane lies in y = 0; a height given had been ignored without a word.
TEST(SceneFieldLimits, APlanesHeightMustBeZero) {
    const std::string plane = R"({"models": {"p": {"type": "plane", "size": [10, Y, 10]}},
                                  "instances": [{"model": "p"}]})";
    for (const char* y : {"5", "-3"}) {
        std::string s = plane;
        EXPECT_EQ(Refusal(s.replace(s.find('Y'), 1, y)),
                  "models.p.size: a plane's size y must be 0 (it lies in y = 0)");
    }
    std::string flat = plane;
    EXPECT_EQ(Refusal(flat.replace(flat.find('Y'), 1, "0")), "");
}

// An instance flattened below 1e-4 of its other sides had rendered wrongly (a box scaled by 1e-6 in
// z shadowed its own lit face, a sphere scaled by 1e-8 lost two thirds of its pixels); a tiny
// uniform scale is fine. A value below float's range is named as written, not as the 0 it becomes.
TEST(SceneFieldLimits, InstancesAreNotFlattenedBeyondWhatFloatsTrace) {
    auto scaled = [](const std::string& scale) {
        return Refusal(R"({"models": {"b": {"type": "box"}},
                           "instances": [{"model": "b", "scale": )" +
                       scale + "}]}");
    };
    const std::string flat =
        "instances[0].scale: the smallest scale factor must be at least 1e-4 "
        "of the largest (size the model instead)";
    EXPECT_EQ(scaled("[1, 1, 1e-6]"), flat);
    EXPECT_EQ(scaled("[1e-3, 20, 1]"), flat);
    EXPECT_EQ(scaled("1e-50"), "instances[0].scale: must be greater than 0, got 1e-50");
    EXPECT_EQ(scaled("[1, 1, 1e-4]"), "");
    EXPECT_EQ(scaled("1e-8"), "");
    EXPECT_EQ(scaled("[2e-8, 1e-8, 1e-8]"), "");
    // The bound comes first where both are broken.
    EXPECT_EQ(scaled("[1e7, 1, 1]"), "instances[0].scale: scale factors must be at most 1e6");
    // Keys of a scale animation are held to the same rule; a uniform pop-in from 1e-6 is fine.
    auto keyed = [](const std::string& key) {
        return Refusal(R"({"models": {"b": {"type": "box"}}, "instances": [{"model": "b",
            "animate": {"keyframes": {"scale": [[0, 1, 1, 1], )" +
                       key + "]}}}]}");
    };
    EXPECT_EQ(keyed("[1, 1, 1e-6, 1]"),
              "instances[0].animate.keyframes.scale[1]: the smallest scale factor must be at "
              "least 1e-4 of the largest");
    EXPECT_EQ(keyed("[1, 1e-6, 1e-6, 1e-6]"), "");
}

// sbvh splits triangles; on a sphere model it had been accepted and ignored.
TEST(SceneFieldLimits, SpatialSplitsAreForTriangleModelsOnly) {
    for (const char* type :
         {R"("type": "sphere")", R"("type": "spheres", "spheres": [[0, 0, 0, 1]])"})
        EXPECT_EQ(Refusal(std::string(R"({"models": {"b": {)") + type +
                          R"(, "builder": "sbvh"}}, "instances": [{"model": "b"}]})"),
                  "models.b.builder: sbvh splits triangles; sphere models take binned, sweep or "
                  "centroid");
    EXPECT_EQ(Refusal(R"({"models": {"b": {"type": "box", "builder": "sbvh"}},
                          "instances": [{"model": "b"}]})"),
              "");
}

class SceneModelFiles : public test::ScratchFolderTest {};

// A folder named as a model file had been reported as an unknown mesh file extension, without the
// scene's field.
TEST_F(SceneModelFiles, AFolderIsNotAModelFile) {
    std::filesystem::create_directories(dir_ / "meshes");
    const std::string base = dir_.string();
    for (const char* file : {".", "meshes"}) {
        const std::string reason =
            Refusal(std::string(R"({"models": {"m": {"type": "mesh", "file": ")") + file +
                        R"("}}, "instances": [{"model": "m"}]})",
                    base);
        EXPECT_EQ(reason, std::string("models.m.file: ") + base + "/" + file +
                              " is not a regular file (a folder)");
    }
}

// A model too small to be fitted had been refused as one whose world bounds were too large.
TEST_F(SceneModelFiles, AModelTooSmallToFitSaysSo) {
    std::ofstream((dir_ / "tiny.obj").string()) << "v 0 0 0\nv 1e-45 0 0\nv 0 1e-45 0\nf 1 2 3\n";
    EXPECT_EQ(Refusal(R"({"models": {"m": {"type": "mesh", "file": "tiny.obj", "fit": 2}},
                          "instances": [{"model": "m"}]})",
                      dir_.string()),
              "models.m.fit: the model's largest extent, 1.4013e-45, is too small to be scaled in "
              "32-bit floats");
    std::ofstream((dir_ / "small.obj").string()) << "v 0 0 0\nv 1e-30 0 0\nv 0 1e-30 0\nf 1 2 3\n";
    EXPECT_EQ(Refusal(R"({"models": {"m": {"type": "mesh", "file": "small.obj", "fit": 2}},
                          "instances": [{"model": "m"}]})",
                      dir_.string()),
              "");
}

}  // namespace
}  // namespace rtrt
