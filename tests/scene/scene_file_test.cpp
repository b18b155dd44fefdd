// Scene files: what parses, and one clear message (file, field, reason) for what does not.
#include "game/scene/scene_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "engine/core/error.h"
#include "engine/render_rt/camera.h"
#include "game/scene/default_scene.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

constexpr const char* kMinimal = R"({
  "models": { "ball": { "type": "sphere", "radius": 2 } },
  "materials": { "m": { "diffuse": [1, 0, 0], "reflectivity": 0.5 } },
  "instances": [ { "model": "ball", "material": "m", "position": [1, 2, 3] } ]
})";

// Expects InputError whose message names the file and field and contains the reason.
void ExpectError(const std::string& json, const std::string& field, const std::string& reason) {
    try {
        ParseScene(json, "bad.json", "");
        FAIL() << "no error for " << json;
    } catch (const InputError& e) {
        EXPECT_EQ(e.File(), "bad.json");
        EXPECT_EQ(e.Field(), field) << e.what();
        EXPECT_NE(e.Reason().find(reason), std::string::npos) << e.what();
    }
}

// The camera between two keys late in a long run: a float clock there moved in steps of 1/64 s
// (150000 s), so a third of the way between the keys was placed at 0.328 of it.
TEST(SceneFile, CameraPathIsInterpolatedAtFullPrecisionLateInARun) {
    const LoadedScene s = ParseScene(R"({"instances": [], "camera_path": [
        {"time": 150000, "position": [-2, 0, 5], "look_at": [0, 0, 0]},
        {"time": 150001, "position": [2, 0, 5], "look_at": [0, 0, 0]}]})",
                                     "late.json", "");
    EXPECT_NEAR(CameraAt(s, 150000.0 + 1.0 / 3.0).position.x, -2.0f + 4.0f / 3.0f, 1e-5f);
    EXPECT_NEAR(CameraAt(s, 150000.0 + 1.0 / 60.0).position.x, -2.0f + 4.0f / 60.0f, 1e-5f);
}

TEST(SceneFile, ParsesAMinimalScene) {
    const LoadedScene s = ParseScene(kMinimal, "ok.json", "");
    ASSERT_EQ(s.scene.instances.size(), 1u);
    EXPECT_EQ(s.scene.instances[0].Position()[1], 2.0f);
    EXPECT_EQ(s.scene.blases[0]->spheres[0].radius, 2.0f);
    EXPECT_EQ(s.scene.materials[0].reflectivity, 0.5f);
    // Ambient defaults to 0.1 x diffuse.
    EXPECT_FLOAT_EQ(s.scene.materials[0].ambient.x, 0.1f);
    EXPECT_EQ(s.scene.Features(), kFeatureReflection);
}

TEST(SceneFile, MalformedJsonNamesTheFile) {
    ExpectError("{ \"instances\": [ }", "", "malformed JSON");
}

TEST(SceneFile, UnknownFieldsAreRejected) {
    ExpectError(R"({"instances": [], "camra": {}})", "camra", "unknown field");
    ExpectError(R"({"instances": [], "camera": {"fov": 40}})", "camera.fov", "unknown field");
}

TEST(SceneFile, MistypedFieldsAreRejected) {
    ExpectError(R"({"instances": [], "camera": {"fov_y": "wide"}})", "camera.fov_y",
                "expected a number, got string");
    ExpectError(R"({"instances": [], "camera": {"position": [0, 1]}})", "camera.position",
                "expected an array of 3 numbers");
    ExpectError(R"({"instances": {}})", "instances", "expected an array");
    ExpectError(R"({"instances": [], "max_depth": 1.5})", "max_depth", "expected an integer");
}

TEST(SceneFile, ImpossibleValuesAreRejected) {
    ExpectError(R"({"instances": [], "image": {"width": 0}})", "image.width",
                "between 1 and 16384");
    ExpectError(R"({"instances": [], "max_depth": 99})", "max_depth", "between 1 and 16");
    ExpectError(R"({"instances": [], "camera": {"fov_y": 180}})", "camera.fov_y", "between");
    ExpectError(R"({"instances": [], "camera": {"forward": [0, 1, 0]}})", "camera.up", "parallel");
    ExpectError(
        R"({"instances": [], "materials": {"m": {"reflectivity": 0.7, "transmissivity": 0.7}}})",
        "materials.m.transmissivity", "must not exceed 1");
    ExpectError(R"({"instances": [], "models": {"b": {"type": "sphere", "radius": -1}}})",
                "models.b.radius", "greater than 0");
}

// Views with no camera basis, and sizes whose squares leave float's range, found by probing: each
// once rendered without an error, background only or with NaN pixels. A tiny or huge up or view
// direction keeps its meaning.
TEST(SceneFile, CamerasWithoutABasisAreRejected) {
    ExpectError(R"({"instances": [], "camera": {"up": [0, 0, 0]}})", "camera.up", "parallel");
    // A camera (or a light) is a place in the scene, as an instance's position is: a view from
    // -3e38 to 3e38 is refused at its position (its length was beyond float's range).
    ExpectError(R"({"instances": [], "camera": {"position": [-3e38, 0, 0]}})", "camera.position",
                "at most 1e7");
    ExpectError(R"({"instances": [], "lights": [{"type": "point", "position": [0, 1e20, 0]}]})",
                "lights[0].position", "at most 1e7");
    ExpectError(R"({"instances": [], "camera": {"look_at": [0, 0, 10]}})", "camera.look_at",
                "zero length");
    // A direction or up of any finite size keeps its meaning.
    const LoadedScene far = ParseScene(
        R"({"instances": [], "camera": {"position": [0, 0, 0], "look_at": [3e38, 3e38, 0],
            "up": [0, 1e-40, 1e-40]}})",
        "far.json", "");
    const CameraFrame frame = MakeCameraFrame(far.scene.camera, 16, 9);
    EXPECT_NEAR(frame.forward.x, 0.70710678f, 1e-6f);
    EXPECT_NEAR(frame.forward.y, 0.70710678f, 1e-6f);
    EXPECT_NEAR(glm::length(frame.right), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(frame.right, frame.forward), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(frame.up), 1.0f, 1e-6f);
}

TEST(SceneFile, CameraPathsWhoseViewTurnsParallelToUpAreRejected) {
    // A key looking straight down.
    ExpectError(R"({"instances": [], "camera_path": [
        {"time": 0, "position": [0, 5, 0], "look_at": [0, 0, 0]}]})",
                "camera_path[0].look_at", "parallel to the camera's up");
    // Keys that look sideways, but the view between them passes straight down (at w = 0.5).
    ExpectError(R"({"instances": [], "camera_path": [
        {"time": 0, "position": [0, 5, 0], "look_at": [-1, 0, 0]},
        {"time": 1, "position": [0, 5, 0], "look_at": [1, 0, 0]}]})",
                "camera_path[1].look_at", "on the way from the key before");
    // look_at passing through position on the way.
    ExpectError(R"({"instances": [], "camera_path": [
        {"time": 0, "position": [0, 0, 0], "look_at": [0, 0, -1]},
        {"time": 1, "position": [0, 0, 0], "look_at": [0, 0, 1]}]})",
                "camera_path[1].look_at", "on the way from the key before");
    // The same through a point where the crossing's weight (59/111) is not exact in binary.
    ExpectError(R"({"instances": [], "camera_path": [
        {"time": 0, "position": [0, 0, -5.9], "look_at": [0, 0, 0]},
        {"time": 1, "position": [0, 0, 5.2], "look_at": [0, 0, 0]}]})",
                "camera_path[1].look_at", "on the way from the key before");
    // A camera that only sets up for a path is not checked against a view it never shows (the
    // default forward, parallel to this up, had refused the file).
    EXPECT_NO_THROW(ParseScene(R"({"instances": [], "camera": {"up": [0, 0, 1]}, "camera_path": [
        {"time": 0, "position": [0, 0, 0], "look_at": [1, 0, 0]},
        {"time": 1, "position": [0, 0, 0], "look_at": [0, 1, 0]}]})",
                               "s.json", ""));
    ExpectError(R"({"instances": [], "camera": {"up": [0, 0, 0]}, "camera_path": [
        {"time": 0, "position": [0, 0, 0], "look_at": [1, 0, 0]}]})",
                "camera.up", "a finite, non-zero direction");
    // With another up, the straight-down view is fine; so is a path that turns beside up.
    EXPECT_NO_THROW(ParseScene(
        R"({"instances": [], "camera": {"forward": [0, -1, 0], "up": [0, 0, -1]}, "camera_path": [
        {"time": 0, "position": [0, 5, 0], "look_at": [0, 0, 0]}]})",
        "down.json", ""));
    EXPECT_NO_THROW(ParseScene(R"({"instances": [], "camera_path": [
        {"time": 0, "position": [0, 5, 10], "look_at": [-1, 0, 0]},
        {"time": 1, "position": [0, 5, 10], "look_at": [1, 0, 0]}]})",
                               "turn.json", ""));
}

TEST(SceneFile, SizesWhoseSquaresOverflowAreRejected) {
    ExpectError(R"({"instances": [], "models": {"b": {"type": "sphere", "radius": 1e20}}})",
                "models.b.radius", "at most 1e6");
    ExpectError(
        R"({"instances": [], "models": {"b": {"type": "spheres", "spheres": [[0, 0, 0, 1e38]]}}})",
        "models.b.spheres[0]", "at most 1e6");
    ExpectError(
        R"({"instances": [], "models": {"b": {"type": "spheres", "spheres": [[1e7, 0, 0, 1]]}}})",
        "models.b.spheres[0]", "at most 1e6");
    ExpectError(
        R"({"instances": [], "lights": [{"type": "point", "position": [0, 1, 0], "color": -1}]})",
        "lights[0].color", "must not be negative");
    // A light direction of any finite size is normalised without overflow.
    const LoadedScene s = ParseScene(
        R"({"instances": [], "lights": [{"type": "directional", "direction": [3e38, 3e38, 3e38]},
            {"type": "directional", "direction": [0, 1e-40, 0]}]})",
        "lights.json", "");
    ASSERT_EQ(s.scene.lights.size(), 2u);
    EXPECT_NEAR(s.scene.lights[0].vector.x, 0.57735027f, 1e-6f);
    EXPECT_NEAR(s.scene.lights[0].vector.z, 0.57735027f, 1e-6f);
    EXPECT_EQ(s.scene.lights[1].vector, vec3(0.0f, 1.0f, 0.0f));
}

// Rigid bodies the simulation's floats cannot handle: a weight whose inverse overflows, a size
// whose inertia underflows or whose bound overflows, a start too far out, a speed whose square
// overflows.
TEST(SceneFile, RigidBodiesBeyondWhatTheSimulationHandlesAreRejected) {
    const auto scene = [](const std::string& model, const std::string& instance) {
        return R"({"models": {"b": )" + model + R"(}, "instances": [)" + instance + "]}";
    };
    const std::string ball = R"({"type": "sphere", "radius": 0.5})";
    ExpectError(scene(ball, R"({"model": "b", "rigid_body": {"mass": 1e-39}})"),
                "instances[0].rigid_body.mass", "at least 1e-6 kg");
    ExpectError(scene(ball, R"({"model": "b", "rigid_body": {"velocity": [2e19, 0, 0]}})"),
                "instances[0].rigid_body.velocity", "within 1e6 m/s");
    ExpectError(scene(ball, R"({"model": "b", "position": [0, 0, 2e5], "rigid_body": {}})"),
                "instances[0].rigid_body", "within 100 km");
    ExpectError(
        scene(R"({"type": "sphere", "radius": 1e-20})", R"({"model": "b", "rigid_body": {}})"),
        "instances[0].rigid_body", "sphere radius");
    ExpectError(
        scene(R"({"type": "box", "size": [4e5, 1, 1]})", R"({"model": "b", "rigid_body": {}})"),
        "instances[0].rigid_body", "box half sides");
    ExpectError(R"({"models": {"b": {"type": "sphere", "radius": 0.5}}, "instances": [],
                    "spawners": [{"model": "b", "position": [90000, 0, 0], "rigid_body": {},
                                  "grid": {"count": [3, 1, 1], "spacing": 1e5}}]})",
                "spawners[0].grid", "beyond 100 km");
    // Found by probing: a ball scaled [3, 0.3, 0.3] rested on its longest axis; "static": "true"
    // was ignored and the body fell; 1,000 balls in one spot took 830 MB a step.
    ExpectError(scene(ball, R"({"model": "b", "scale": [3, 0.3, 0.3], "rigid_body": {}})"),
                "instances[0].rigid_body", "uniform scale");
    ExpectError(scene(ball, R"({"model": "b", "rigid_body": {"mass": 0, "velocity": [3, 0, 0]}})"),
                "instances[0].rigid_body.velocity", "a static body does not move");
    ExpectError(scene(R"({"type": "plane"})", R"({"model": "b", "rigid_body": {"mass": 5}})"),
                "instances[0].rigid_body.mass", "a plane is always static");
    // A plane's velocity was dropped silently (its mass became 0 after the check); a mass that
    // is 0 as a float made a body static; a mass past the bound by less than a float's step was
    // shown as the bound itself.
    ExpectError(
        scene(R"({"type": "plane"})", R"({"model": "b", "rigid_body": {"velocity": [0, 5, 0]}})"),
        "instances[0].rigid_body.velocity", "a plane is always static");
    ExpectError(scene(ball, R"({"model": "b", "rigid_body": {"mass": 1e-50}})"),
                "instances[0].rigid_body.mass", "a moving body weighs at least 1e-6 kg");
    ExpectError(scene(ball, R"({"model": "b", "rigid_body": {"mass": 1.0000001e9}})"),
                "instances[0].rigid_body.mass", "got 1000000100");
    ExpectError(scene(ball, R"({"model": "b", "rigid_body": {"static": "true"}})"),
                "instances[0].rigid_body.static", "expected true or false, got string");
    // Contradictions were settled silently: a static body's mass dropped, "static": false with
    // mass 0 made the body static, and a plane took "static": false.
    ExpectError(scene(ball, R"({"model": "b", "rigid_body": {"static": true, "mass": 5}})"),
                "instances[0].rigid_body.mass", "a static body has no mass");
    ExpectError(scene(ball, R"({"model": "b", "rigid_body": {"static": false, "mass": 0}})"),
                "instances[0].rigid_body.static", "a body of mass 0 is static");
    ExpectError(scene(R"({"type": "plane"})", R"({"model": "b", "rigid_body": {"static": false}})"),
                "instances[0].rigid_body.static", "a plane is always static");
    ExpectError(R"({"models": {"b": {"type": "sphere", "radius": 0.5}}, "instances": [],
                    "spawners": [{"model": "b", "rigid_body": {},
                                  "grid": {"count": [10, 10, 10], "spacing": 1e-6}}]})",
                "spawners[0].rigid_body",
                "1000 rigid bodies that start between 0 and 1 s (so maybe in one frame) overlap "
                "in more than");
    ExpectError(R"({"models": {"b": {"type": "sphere", "radius": 0.5}}, "instances": [],
                    "spawners": [{"model": "b", "rigid_body": {"static": true},
                                  "grid": {"count": [50, 1, 50], "spacing": 2}},
                                 {"model": "b", "rigid_body": {}, "position": [0, 9, 0],
                                  "grid": {"count": [10, 10, 10], "spacing": 1e-6}}]})",
                "spawners[1].rigid_body", "3500 rigid bodies");  // the packed one, not the most
    // Bodies of different times that one frame spawns together count together (two packed
    // spawners 1 ms apart, each within the limit alone, took 763 MB in three frames).
    const std::string packed480 =
        R"("rigid_body": {}, "grid": {"count": [8, 6, 10], "spacing": 0.001}})";
    ExpectError(R"({"models": {"b": {"type": "sphere", "radius": 0.5}}, "instances": [],
                    "spawners": [{"model": "b", "time": 1.5, )" +
                    packed480 + R"(, {"model": "b", "time": 2.2, )" + packed480 + "]}",
                "spawners[0].rigid_body", "960 rigid bodies that start between 1 and 3 s");
    // Many bodies apart are not packed, however many meet on one axis (a 40^3 lattice of
    // touching balls, 64,000); nor are bodies of one place that appear at different times, or
    // static ones, which never pair with each other.
    EXPECT_NO_THROW(ParseScene(R"({"models": {"b": {"type": "sphere", "radius": 0.5}},
                    "instances": [], "spawners": [{"model": "b", "rigid_body": {},
                                  "grid": {"count": [40, 40, 40], "spacing": 1}}]})",
                               "s.json", ""));
    std::string apartInTime = R"({"models": {"b": {"type": "sphere"}}, "instances": [],
                                  "spawners": [)";
    for (int i = 0; i < 600; ++i)
        apartInTime += (i ? ", " : "") +
                       std::string(R"({"model": "b", "rigid_body": {}, "time": )") +
                       std::to_string(i) + R"(, "grid": {"count": [1, 1, 1]}})";
    EXPECT_NO_THROW(ParseScene(apartInTime + "]}", "s.json", ""));
    EXPECT_NO_THROW(ParseScene(R"({"models": {"b": {"type": "box"}}, "instances": [],
                    "spawners": [{"model": "b", "rigid_body": {"static": true},
                                  "grid": {"count": [10, 10, 10], "spacing": 1e-6}}]})",
                               "s.json", ""));
    // The same bodies without a rigid body are only drawn, and a static one may weigh nothing.
    EXPECT_NO_THROW(
        ParseScene(scene(ball, R"({"model": "b", "position": [0, 0, 2e5]})"), "s.json", ""));
    EXPECT_NO_THROW(
        ParseScene(scene(ball, R"({"model": "b", "rigid_body": {"mass": 0}})"), "s.json", ""));
}

// Extents beyond what 32-bit floats trace well are refused by field: a plane of side 1e10 rendered
// as if in shadow and one of 1e15 not at all, a sphere scaled by 1e15 vanished, and a negative
// box side made the box of its magnitude.
TEST(SceneFile, ExtentsBeyondWhatFloatsTraceAreRejected) {
    const auto scene = [](const std::string& model, const std::string& instance) {
        return R"({"models": {"m": )" + model + R"(}, "instances": [)" + instance + "]}";
    };
    ExpectError(scene(R"({"type": "plane", "size": [1e10, 0, 1]})", R"({"model": "m"})"),
                "models.m.size", "at most 1e6");
    ExpectError(scene(R"({"type": "box", "size": [1, 2e6, 1]})", R"({"model": "m"})"),
                "models.m.size", "at most 1e6");
    ExpectError(scene(R"({"type": "box", "size": [1, -1, 1]})", R"({"model": "m"})"),
                "models.m.size", "greater than 0");
    ExpectError(scene(R"({"type": "teapot", "fit": 1e7})", R"({"model": "m"})"), "models.m.fit",
                "at most 1e6");
    ExpectError(scene(R"({"type": "sphere"})", R"({"model": "m", "scale": 1e15})"),
                "instances[0].scale", "at most 1e6");
    ExpectError(scene(R"({"type": "sphere"})", R"({"model": "m", "position": [0, -2e7, 0]})"),
                "instances[0].position", "at most 1e7");
    // An empty file name had been read as the scene's folder ("unknown mesh file extension").
    ExpectError(R"({"models": {"m": {"type": "mesh", "file": ""}}, "instances": []})",
                "models.m.file", "is empty; name a model file");
    // A rain of tiny bodies makes more cells than an int holds: said so, not "holds only 0".
    ExpectError(R"({"models": {"b": {"type": "sphere"}}, "instances": [],
                    "spawners": [{"model": "b", "scale": 1e-30,
                                  "rain": {"count": 10, "min": [-1, -1, -1], "max": [1, 1, 1]}}]})",
                "spawners[0].rain", "too large for bodies of this size (over 50M cells)");
    // Counts past int64's range are shown as written (2^64 - 1 was "got -1").
    ExpectError(R"({"max_depth": 18446744073709551615, "instances": []})", "max_depth",
                "must be between 1 and 16, got 18446744073709551615");
    EXPECT_NO_THROW(ParseScene(scene(R"({"type": "plane", "size": [1e6, 0, 1e6]})",
                                     R"({"model": "m", "scale": 1e6, "position": [1e7, 0, 0]})"),
                               "s.json", ""));
}

// Found by probing: animation keys, motions, deformations and spawner places went around the
// bounds an instance's own fields have, and the object vanished (a key at 1e20, a scale of 1e30,
// an orbit of radius 1e20, a wavelength of 1e-45 that made every vertex NaN, a grid spacing of
// 1e20); a key time of 1e300 was called "not finite".
TEST(SceneFile, AnimationsDeformationsAndSpawnsStayWithinTheSceneBounds) {
    const auto animated = [](const std::string& animate) {
        return R"({"models": {"m": {"type": "sphere"}}, "instances": [{"model": "m", "animate": )" +
               animate + "}]}";
    };
    const std::string keys = "instances[0].animate.keyframes.";
    ExpectError(animated(R"({"keyframes": {"translation": [[0, 0, 0, 0], [1, 1e20, 0, 0]]}})"),
                keys + "translation[1]", "at most 1e7 in magnitude");
    ExpectError(animated(R"({"keyframes": {"scale": [[0, 1, 1, 1], [1, 1e30, 1, 1]]}})"),
                keys + "scale[1]", "between 1e-6 and 1e6");
    ExpectError(animated(R"({"keyframes": {"scale": [[0, 0, 1, 1]]}})"), keys + "scale[0]",
                "between 1e-6 and 1e6");
    ExpectError(animated(R"({"keyframes": {"rotation": [[0, 0, 0, 0], [1, 1e300, 0, 0]]}})"),
                keys + "rotation[1]", "within float's range");
    ExpectError(animated(R"({"keyframes": {"translation": [[1e300, 0, 0, 0]]}})"),
                keys + "translation[0]", "within float's range");
    ExpectError(animated(R"({"orbit": {"radius": 1e20}})"), "instances[0].animate.orbit.radius",
                "between");
    ExpectError(animated(R"({"orbit": {"centre": [3e38, 0, 0]}})"),
                "instances[0].animate.orbit.centre", "at most 1e7");
    ExpectError(animated(R"({"bob": {"amplitude": 3e38}})"), "instances[0].animate.bob.amplitude",
                "between");
    const auto deformed = [](const std::string& deform) {
        return R"({"models": {"m": {"type": "box"}}, "instances": [{"model": "m", "deform": )" +
               deform + "}]}";
    };
    ExpectError(deformed(R"({"wave": {"amplitude": 0.1, "wavelength": 1e-45}})"),
                "instances[0].deform.wave.wavelength", "between 1e-6 and 1e7");
    ExpectError(deformed(R"({"wave": {"amplitude": 0.1, "wavelength": 1, "phase": 3e38}})"),
                "instances[0].deform.wave.phase", "between");
    ExpectError(
        deformed(R"({"wave": {"amplitude": 0.1, "wavelength": 1, "centre": [3e38, 0, 0]}})"),
        "instances[0].deform.wave.centre", "at most 1e7");
    ExpectError(R"({"models": {"m": {"type": "sphere"}}, "instances": [],
                    "spawners": [{"model": "m", "grid": {"count": [3, 1, 1], "spacing": 1e20}}]})",
                "spawners[0].grid.spacing", "beyond 1e7");
    ExpectError(R"({"models": {"m": {"type": "sphere"}}, "instances": [],
                    "spawners": [{"model": "m", "rain": {"count": 1, "min": [5e8, 0, 0],
                                                         "max": [5e8, 5, 5]}}]})",
                "spawners[0].rain.min", "at most 1e7");
    EXPECT_NO_THROW(
        ParseScene(animated(R"({"keyframes": {"translation": [[0, 0, 0, 0], [1, 1e7, 0, 0]],
                                  "scale": [[0, 1e-6, 1e-6, 1e-6], [1, 1e6, 1e6, 1e6]]}})"),
                   "s.json", ""));
    EXPECT_NO_THROW(ParseScene(
        animated(R"({"keyframes": {"scale": [[0, 1e6, 1e6, 1e6]]}, "orbit": {"radius": 1e7}})"),
        "s.json", ""));
    // Axes far from unit length keep their direction (one of 1e20 had become +y, one of 1e-30 was
    // refused as zero).
    for (const char* axis : {"[1e20, 0, 0]", "[1e-30, 0, 0]"}) {
        const LoadedScene spun =
            ParseScene(animated(std::string(R"({"spin": {"axis": )") + axis + R"(, "speed": 1}})"),
                       "s.json", "");
        const auto& spin = std::get<physics::Spin>(spun.entities.at(0).animator->motions.at(0));
        EXPECT_EQ(spin.axis, vec3(1, 0, 0)) << axis;
    }
    // An orbit sets the position itself: translation keys beside it would do nothing.
    ExpectError(animated(R"({"keyframes": {"translation": [[0, 0, 0, 0], [1, 1, 0, 0]]},
                             "orbit": {"radius": 1}})"),
                "instances[0].animate.orbit", "give translation keys or an orbit, not both");
}

TEST(SceneFile, DanglingReferencesAreRejected) {
    ExpectError(R"({"instances": [{"model": "nothing"}]})", "instances[0].model", "no model named");
    ExpectError(
        R"({"models": {"b": {"type": "sphere"}}, "instances": [{"model": "b", "material": "x"}]})",
        "instances[0].material", "no material named");
    ExpectError(R"({"models": {"b": {"type": "cone"}}, "instances": []})", "models.b.type",
                "unknown model type");
    ExpectError(R"({"instances": []}, "lights": [{"type": "spot"}])", "", "malformed JSON");
    ExpectError(R"({"instances": [], "lights": [{"type": "area"}]})", "lights[0].type",
                "unknown light type");
}

TEST(SceneFile, PointAndSpotLightsOptInToFalloff) {
    const LoadedScene s = ParseScene(R"({"instances": [], "lights": [
        {"type": "point", "position": [0, 2, 0]},
        {"type": "point", "position": [0, 2, 0], "falloff": "inverse_square", "range": 5},
        {"type": "spot", "position": [0, 2, 0], "direction": [0, -2, 0], "inner_cone": 10,
         "outer_cone": 30, "falloff": "inverse_square", "color": [10, 10, 10]}]})",
                                     "lights.json", "");
    const auto& lights = s.scene.lights;
    ASSERT_EQ(lights.size(), 3u);
    EXPECT_EQ(lights[0].falloff, 0u);  // as rtrt's point lights always were
    EXPECT_FALSE(LightAttenuates(lights[0]));
    EXPECT_EQ(lights[1].falloff, 1u);
    EXPECT_EQ(lights[1].range, 5.0f);
    EXPECT_EQ(lights[2].type, LightType::kSpot);
    EXPECT_EQ(lights[2].spotAxis, vec3(0, -1, 0));
    // Straight below at distance 2: 1/4; 20 degrees off the axis: half way through the cone.
    EXPECT_FLOAT_EQ(LightAttenuation(lights[2], vec3(0, 2, 0), vec3(0, 1, 0)), 0.25f);
    const float a = 20.0f * kPi / 180.0f;
    const vec3 l(std::sin(a), std::cos(a), 0.0f);
    const float w = (std::cos(a) - std::cos(kPi / 6)) / (std::cos(kPi / 18) - std::cos(kPi / 6));
    EXPECT_NEAR(LightAttenuation(lights[2], l, l), w * w, 1e-5f);
    ExpectError(R"({"instances": [], "lights": [{"type": "point", "position": [0, 0, 0],
        "falloff": "linear"}]})",
                "lights[0].falloff", "unknown falloff");
    ExpectError(R"({"instances": [], "lights": [{"type": "spot", "position": [0, 0, 0],
        "direction": [0, 0, 1], "inner_cone": 40, "outer_cone": 30}]})",
                "lights[0].inner_cone", "between");
    ExpectError(R"({"instances": [], "lights": [{"type": "point", "position": [0, 0, 0],
        "range": 3}]})",
                "lights[0].range", "unknown field");
}

TEST(SceneFile, MissingRequiredFieldsAreNamed) {
    ExpectError(R"({})", "instances", "missing required field");
    ExpectError(R"({"instances": [], "lights": [{"type": "point"}]})", "lights[0].position",
                "missing required field");
}

TEST(SceneFile, MissingFilesAreReported) {
    try {
        LoadSceneFile("/nonexistent/scene.json");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.File(), "/nonexistent/scene.json");
        EXPECT_EQ(e.Reason(), "no such file");
    }
    try {
        ParseScene(R"({"models": {"m": {"type": "mesh", "file": "missing.obj"}}, "instances": []})",
                   "scene.json", "/nonexistent");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.File(), "scene.json") << e.what();
        EXPECT_EQ(e.Field(), "models.m.file") << e.what();
        EXPECT_EQ(e.Reason(),
                  "no file /nonexistent/missing.obj (a relative path starts at the scene file's "
                  "folder)");
    }
}

// A device would be read for ever and a FIFO would block the open: both are refused at once.
TEST(SceneFile, WhatIsNotARegularFileIsRefused) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("rtrt_scene_fifo_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    const std::string fifo = (dir / "scene.json").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const std::string& path : {fifo, std::string("/dev/zero")}) {
        try {
            LoadSceneFile(path);
            ADD_FAILURE() << path << ": loaded";
        } catch (const InputError& e) {
            EXPECT_EQ(e.File(), path);
            EXPECT_EQ(e.Reason(), "not a regular file") << e.what();
        }
    }
    std::filesystem::remove_all(dir);
}

TEST(SceneFile, MeshesWithBadDataAreRejected) {
    const auto dir = std::filesystem::temp_directory_path() / "rtrt_scene_file_test";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "nan.obj") << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
    std::ofstream(dir / "empty.obj") << "v 0 0 0\nv 1 0 0\n";
    for (const char* name : {"nan.obj", "empty.obj"}) {
        const std::string json = std::string(R"({"models": {"m": {"type": "mesh", "file": ")") +
                                 name + R"("}}, "instances": [{"model": "m"}]})";
        try {
            ParseScene(json, "scene.json", dir.string());
            FAIL() << name;
        } catch (const InputError& e) {
            EXPECT_NE(e.File().find(name), std::string::npos) << e.what();
        }
    }
}

// Every scene under assets/scenes, the full-dragon ones too (a second or so each): none may be
// left out unless the models it names are not fetched, which is then a skip that says so.
TEST(SceneFile, EveryShippedSceneParses) {
    int scenes = 0, parsed = 0;
    std::string unfetched;
    for (const auto& entry :
         std::filesystem::directory_iterator(test::SourcePath("assets/scenes"))) {
        if (entry.path().extension() != ".json") continue;
        ++scenes;
        const std::string text = entry.path().filename().string();
        std::ifstream in(entry.path());
        const std::string content((std::istreambuf_iterator<char>(in)), {});
        const bool needsTeapot = content.find("teapot") != std::string::npos;
        const bool needsDragon = content.find("dragon_vrip") != std::string::npos;
        if ((needsTeapot && test::FetchedModel("teapot.inc").empty()) ||
            (needsDragon && test::FetchedModel("dragon_vrip.ply.gz").empty())) {
            unfetched += " " + text;
            continue;
        }
        SCOPED_TRACE(text);
        EXPECT_NO_THROW(LoadSceneFile(entry.path().string()));
        ++parsed;
    }
    EXPECT_GE(scenes, 13);
    if (!unfetched.empty()) GTEST_SKIP() << "models not fetched for" << unfetched;
    EXPECT_EQ(parsed, scenes);
}

// Rains that give no seed each get their own (n for the n-th rain): with one default seed
// for all, two rains over one region put every body of one inside a body of the other.
TEST(SceneFile, RainsWithoutASeedFallAtDifferentPlaces) {
    const std::string rain = R"({"model": "b", "rain": {"count": 20, "min": [-4, 1, -4],
                                                       "max": [4, 6, 4]SEED}})";
    auto places = [&](const std::string& first, const std::string& second) {
        std::string text = R"({"models": {"b": {"type": "sphere", "radius": 0.5}},
                               "instances": [], "spawners": [)";
        for (int i = 0; i < 2; ++i) {
            std::string one = rain;
            one.replace(one.find("SEED"), 4, i == 0 ? first : second);
            text += one + (i == 0 ? "," : "]}");
        }
        std::vector<std::vector<vec3>> out(2);
        for (const EntityDesc& e : ParseScene(text, "rain.json", "").entities)
            out[e.sourceIndex].push_back(e.local.translation);
        return out;
    };
    const auto unseeded = places("", "");
    ASSERT_EQ(unseeded[0].size(), 20u);
    ASSERT_EQ(unseeded[1].size(), 20u);
    for (const vec3& p : unseeded[1])
        EXPECT_EQ(std::count(unseeded[0].begin(), unseeded[0].end(), p), 0);
    const auto seeded = places(R"(, "seed": 1)", R"(, "seed": 2)");
    EXPECT_EQ(seeded, unseeded);  // the first keeps seed 1, as before
}

// The built-in scene names its materials as a scene file would (rtrt info lists them).
TEST(SceneFile, DefaultSceneNamesItsMaterials) {
    const LoadedScene scene = MakeDefaultLoadedScene();
    ASSERT_EQ(scene.materialNames.size(), scene.scene.materials.size());
    EXPECT_EQ(scene.materialNames[1], "mirror");
    EXPECT_GT(scene.scene.materials[1].reflectivity, 0.5f);
    EXPECT_EQ(scene.materialNames[2], "glass");
    EXPECT_GT(scene.scene.materials[2].transmissivity, 0.5f);
    EXPECT_EQ(scene.materialNames[4], "red");
    EXPECT_GT(scene.scene.materials[4].diffuse.x, scene.scene.materials[4].diffuse.y);
}

// The committed hostile scene files (tests/data/hostile_scene/, seeds of the scene-file fuzz
// target): each gives one InputError naming its file and field.
TEST(SceneFile, HostileSceneFiles) {
    const std::string dir = test::SourcePath("tests/data/hostile_scene");
    const struct {
        const char* name;
        const char* file;  // the file the error names, relative to dir
        const char* field;
        const char* reason;
    } cases[] = {
        {"truncated.json", "truncated.json", "", "malformed JSON"},
        {"wrong_type.json", "wrong_type.json", "models.b.radius", "expected a number, got string"},
        {"huge_number.json", "huge_number.json", "instances[0].position[1]", "out of range"},
        {"zero_scale.json", "zero_scale.json", "instances[0].scale", "greater than 0"},
        {"unknown_model.json", "unknown_model.json", "instances[0].model", "no model named"},
        {"unknown_field.json", "unknown_field.json", "instances[0].colour", "unknown field"},
        {"missing_mesh.json", "missing_mesh.json", "models.m.file",
         "no_such_mesh.obj (a relative path starts at the scene file's folder)"},
        {"hostile_gltf_model.json", "../hostile_gltf/cyclic_nodes.gltf", "nodes[2].children[0]",
         "two parents"},
        {"gltf_with_material.json", "gltf_with_material.json", "instances[0].material",
         "brings its own materials"},
        {"gltf_spawner.json", "gltf_spawner.json", "spawners[0].rain", "glTF scene"},
        {"huge_grid.json", "huge_grid.json", "spawners[0].grid.count", "at most 2,000,000"},
        {"gltf_grid_too_many_entities.json", "gltf_grid_too_many_entities.json",
         "spawners[0].grid.count", "a scene may have at most 2,000,000"},
        {"keys_out_of_order.json", "keys_out_of_order.json", "instances[0].animate.keyframes",
         "increase"},
        {"degenerate_camera.json", "degenerate_camera.json", "camera.look_at", "zero length"},
        {"infinite_bounds.json", "infinite_bounds.json", "instances[1].scale", "at most 1e6"},
        {"number_overflow.json", "number_overflow.json", "", "malformed JSON"},
        {"not_an_object.json", "not_an_object.json", "", "expected an object"},
    };
    EXPECT_NO_THROW(LoadSceneFile(dir + "/valid.json"));
    for (const auto& c : cases) {
        try {
            LoadSceneFile(dir + "/" + c.name);
            ADD_FAILURE() << c.name << ": loaded without an error";
        } catch (const InputError& e) {
            EXPECT_EQ(e.File(), dir + "/" + c.file) << c.name << ": " << e.what();
            EXPECT_EQ(e.Field(), c.field) << c.name << ": " << e.what();
            EXPECT_NE(e.Reason().find(c.reason), std::string::npos) << c.name << ": " << e.what();
        }
    }
}

}  // namespace
}  // namespace rtrt
