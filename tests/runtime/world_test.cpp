// The runtime: scenes play deterministically, extraction touches only what moved, spawners and the
// camera path act on time.
#include "game/runtime/world.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "engine/core/error.h"
#include "engine/physics_anim/animator.h"
#include "engine/physics_anim/transform_system.h"
#include "engine/render_rt/frame_renderer.h"
#include "engine/render_rt/renderer.h"
#include "game/scene/scene_file.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

constexpr const char* kPhysics = R"({
  "camera": { "position": [0, 4, 10], "look_at": [0, 1, 0] },
  "lights": [ { "type": "directional", "direction": [1, 2, 1] } ],
  "models": { "floor": { "type": "plane", "size": [20, 0, 20] },
              "ball": { "type": "sphere", "radius": 0.3 },
              "crate": { "type": "box", "size": [0.5, 0.5, 0.5] } },
  "instances": [ { "model": "floor", "rigid_body": { "static": true } } ],
  "spawners": [
    { "model": "ball", "rain": { "count": 60, "min": [-2, 2, -2], "max": [2, 6, 2], "seed": 3 },
      "rigid_body": { "restitution": 0.5 } },
    { "model": "crate", "time": 0.25, "rain": { "count": 10, "min": [-2, 6, -2], "max": [2, 8, 2] },
      "rigid_body": {} } ]
})";

constexpr const char* kAnimated = R"({
  "models": { "ball": { "type": "sphere" }, "box": { "type": "box" } },
  "instances": [ { "model": "box", "position": [5, 0, 0] } ],
  "spawners": [ { "model": "ball", "grid": { "count": [4, 4, 4], "spacing": 3 },
                  "animate": { "spin": { "speed": 2 } } } ],
  "camera_path": [ { "time": 0, "position": [0, 0, 20], "look_at": [0, 0, 0] },
                   { "time": 2, "position": [20, 0, 0], "look_at": [0, 0, 0] } ]
})";

std::vector<Image> Play(const LoadedScene& scene, int frames) {
    World world(scene);
    const std::unique_ptr<FrameRenderer> renderer = MakeFrameRenderer(Backend::kCpu, world.Scene());
    RenderSettings s;
    s.width = 96;
    s.height = 64;
    s.maxDepth = 2;
    std::vector<Image> images;
    for (int i = 0; i < frames; ++i) {
        if (i > 0) {
            world.Advance(1.0f / 60.0f);
            renderer->Update(world.Scene(), world.Changes());
        }
        images.emplace_back();
        renderer->Trace(world.Scene(), s, &images.back());
    }
    return images;
}

TEST(World, SameSceneAndFrameCountGiveIdenticalImages) {
    const LoadedScene scene = ParseScene(kPhysics, "physics.json", "");
    const std::vector<Image> a = Play(scene, 40), b = Play(scene, 40);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i)
        ASSERT_EQ(
            std::memcmp(a[i].pixels.data(), b[i].pixels.data(), a[i].pixels.size() * sizeof(vec3)),
            0)
            << "frame " << i;
    // And the scene really moved: the first and last frames differ.
    EXPECT_NE(std::memcmp(a.front().pixels.data(), a.back().pixels.data(),
                          a.front().pixels.size() * sizeof(vec3)),
              0);
}

// Entities are ordered by the time they appear, their links (parents, skin joints) renumbered with
// them: a glTF spawner listed after a later one's plays as when listed first (its node tree moved
// past the later bodies and kept the old parent indices: the walkers' limbs were tangled).
TEST(World, SpawnerOrderDoesNotChangeTheScene) {
    const std::string walkers =
        R"({ "model": "walker", "grid": { "count": [2, 1, 1], "spacing": 1.5 }, "phase_spread": 1 })";
    const std::string balls =
        R"({ "model": "ball", "time": 0.02, "grid": { "count": [3, 1, 1], "spacing": 1 },
             "position": [0, 3, 0] })";
    auto scene = [&](const std::string& first, const std::string& second) {
        return ParseScene(R"({ "camera": { "position": [0, 1, 6], "look_at": [0, 1, 0] },
          "models": { "walker": { "type": "gltf", "file": "walker.gltf" },
                      "ball": { "type": "sphere", "radius": 0.2 } },
          "instances": [], "spawners": [ )" +
                              first + ", " + second + " ] }",
                          "order.json", test::SourcePath("assets/models"));
    };
    const std::vector<Image> walkersFirst = Play(scene(walkers, balls), 4);
    const std::vector<Image> ballsFirst = Play(scene(balls, walkers), 4);
    for (size_t f = 0; f < walkersFirst.size(); ++f) {
        size_t differ = 0;
        for (size_t p = 0; p < walkersFirst[f].pixels.size(); ++p)
            differ += walkersFirst[f].pixels[p] != ballsFirst[f].pixels[p];
        EXPECT_EQ(differ, 0u) << "frame " << f;
    }
}

TEST(World, SpawnersActOnTimeAndBodiesFall) {
    const LoadedScene scene = ParseScene(kPhysics, "physics.json", "");
    World world(scene);
    EXPECT_EQ(world.Scene().instances.size(), 61u);  // floor + 60 balls at time 0
    FrameStats stats{};
    for (int i = 0; i < 15; ++i) stats = world.Advance(1.0f / 60.0f);  // t = 0.25
    EXPECT_EQ(world.Scene().instances.size(), 71u);                    // the crates arrived
    for (int i = 0; i < 60; ++i) world.Advance(1.0f / 60.0f);
    // Every ball is above the floor and below where the rain started.
    for (size_t i = 1; i < 61; ++i) {
        const float y = world.Scene().instances[i].Position()[1];
        EXPECT_GT(y, 0.29f);
        EXPECT_LT(y, 6.0f);
    }
}

TEST(World, ExtractionTouchesOnlyWhatMoved) {
    const LoadedScene scene = ParseScene(kAnimated, "animated.json", "");
    World world(scene);
    const FrameStats stats = world.Advance(0.1f);
    EXPECT_EQ(stats.extracted, 64u);  // the spinning balls, not the static box
    EXPECT_EQ(world.Scene().instances.size(), 65u);
    const Instance before = world.Scene().instances[0];  // the box, placed first
    world.Advance(0.1f);
    EXPECT_EQ(std::memcmp(&before, &world.Scene().instances[0], sizeof(Instance)), 0);
}

TEST(World, CameraFollowsItsPath) {
    const LoadedScene scene = ParseScene(kAnimated, "animated.json", "");
    World world(scene);
    for (int i = 0; i < 10; ++i) world.Advance(0.1f);  // t = 1: halfway
    EXPECT_NEAR(world.Scene().camera.position.x, 10.0f, 1e-4f);
    EXPECT_NEAR(world.Scene().camera.position.z, 10.0f, 1e-4f);
}

TEST(World, KeyframesMoveAnEntity) {
    const LoadedScene scene = ParseScene(R"({
      "models": { "ball": { "type": "sphere" } },
      "instances": [ { "model": "ball", "animate": { "keyframes": {
          "translation": [[0, 0, 0, 0], [1, 0, 4, 0]], "loop": true } } } ] })",
                                         "keys.json", "");
    World world(scene);
    for (int i = 0; i < 5; ++i) world.Advance(0.125f);  // t = 0.625: linear between the keys
    EXPECT_NEAR(world.Scene().instances[0].Position()[1], 2.5f, 1e-5f);
    for (int i = 0; i < 4; ++i) world.Advance(0.125f);  // t = 1.125: looped to 0.125
    EXPECT_NEAR(world.Scene().instances[0].Position()[1], 0.5f, 1e-5f);
}

// A keyframed spawner's copies each play the keys from their own place (all had played them at
// the same place), and a spawned entity's animation runs from the time it is due, so that its
// pose at a given time is the same at any frame rate (it had started a step late).
TEST(World, SpawnedKeyframesKeepTheirPlaceAndTheirTime) {
    const LoadedScene scene = ParseScene(R"({
      "models": { "ball": { "type": "sphere", "radius": 0.1 } }, "instances": [],
      "spawners": [ { "model": "ball", "time": 0.45, "position": [0, 0, 0],
                      "grid": { "count": [3, 1, 1], "spacing": 1.5 },
                      "animate": { "keyframes": { "translation": [[0, 0, 0, 0], [2, 2, 0, 0]] } } } ] })",
                                         "spawned_keys.json", "");
    for (const int fps : {4, 10, 20}) {
        World world(scene);
        for (int i = 0; i < fps; ++i) world.Advance(1.0f / float(fps));  // t = 1
        std::vector<float> x;
        for (const Instance& inst : world.Scene().instances) x.push_back(inst.Position()[0]);
        std::sort(x.begin(), x.end());
        ASSERT_EQ(x.size(), 3u) << fps;
        // 0.55 s into keys that move x by 1 per second, from places -1.5, 0 and 1.5.
        EXPECT_NEAR(x[0], -1.5f + 0.55f, 1e-5f) << fps << " fps";
        EXPECT_NEAR(x[1], 0.55f, 1e-5f) << fps << " fps";
        EXPECT_NEAR(x[2], 1.5f + 0.55f, 1e-5f) << fps << " fps";
    }
}

// An animated entity shows its animation's pose from the first frame, in the loaded scene that
// render draws and in a World before its first step: it had shown its own "position" there, and
// the second frame jumped to the animation.
TEST(World, AnimatedEntitiesArePosedAtTimeZero) {
    const LoadedScene scene = ParseScene(R"({
      "models": { "ball": { "type": "sphere" } },
      "instances": [ { "model": "ball", "position": [0, 9, 0], "animate": {
          "keyframes": { "translation": [[0, 3, 0, 0], [1, 5, 0, 0]] } } },
        { "model": "ball", "animate": { "orbit": { "centre": [0, 0, 0], "radius": 2 } } } ] })",
                                         "posed.json", "");
    EXPECT_EQ(scene.scene.instances[0].Position(), glm::vec3(3.0f, 0.0f, 0.0f));
    EXPECT_NEAR(glm::length(scene.scene.instances[1].Position()), 2.0f, 1e-5f);
    World world(scene);
    EXPECT_EQ(world.Scene().instances[0].Position(), glm::vec3(3.0f, 0.0f, 0.0f));
    EXPECT_NEAR(glm::length(world.Scene().instances[1].Position()), 2.0f, 1e-5f);
    world.Advance(0.5f);
    EXPECT_NEAR(world.Scene().instances[0].Position()[0], 4.0f, 1e-5f);
}

// A rotated plane in a scene file is a wall: its collider was turned by the rotation twice, so a
// wall at 90 degrees collided as a ceiling's half-space and drove a falling ball through the floor.
TEST(World, RotatedStaticPlanesCollideWhereTheyAreDrawn) {
    const LoadedScene scene = ParseScene(R"({
      "models": { "floor": { "type": "plane" }, "ball": { "type": "sphere", "radius": 0.5 } },
      "instances": [
        { "model": "floor", "rigid_body": { "static": true } },
        { "model": "floor", "position": [3, 0, 0], "rotation": [0, 0, 90],
          "rigid_body": { "static": true } },
        { "model": "ball", "position": [0, 3, 0], "rigid_body": {} },
        { "model": "ball", "position": [1, 0.5, 1], "rigid_body": { "velocity": [8, 0, 0] } } ]
    })",
                                         "walls.json", "");
    World world(scene);
    float maxX = 0.0f;
    for (int frame = 0; frame < 180; ++frame) {
        world.Advance(1.0f / 60.0f);
        maxX = std::max(maxX, world.Scene().instances[3].Position()[0]);
    }
    EXPECT_NEAR(world.Scene().instances[2].Position()[1], 0.5f, 0.02f);
    EXPECT_LT(maxX, 2.55f);
    EXPECT_GT(maxX, 2.4f);
}

// A rigid body spawned at a time inside a frame joins the simulation at that time: it had been
// stepped through the whole frame that found it due, so at 7 fps a ball due at 1.5 s had fallen
// 0.36 m further by 2 s than at 120 fps, and at 1 fps it had landed.
TEST(World, SpawnedBodiesFallFromTheirOwnTimeAtAnyFrameRate) {
    const LoadedScene scene = ParseScene(R"({
      "models": { "ball": { "type": "sphere", "radius": 0.5 } }, "instances": [],
      "spawners": [ { "model": "ball", "position": [2, 5, 0], "time": 1.5,
                      "grid": { "count": [1, 1, 1] }, "rigid_body": {} } ]
    })",
                                         "late_ball.json", "");
    const float fallen = 5.0f - 0.5f * 9.81f * 0.25f;  // 0.5 s after it appeared
    for (int fps : {1, 7, 60, 120}) {
        World world(scene);
        world.PlayAtFixedFrames(1.0f / float(fps));
        for (int frame = 0; frame < 2 * fps; ++frame) world.Advance(1.0f / float(fps));
        ASSERT_EQ(world.Scene().instances.size(), 1u) << fps;
        // The rendered pose lags the simulation by less than one 1/120 s step.
        EXPECT_NEAR(world.Scene().instances[0].Position()[1], fallen, 0.05f) << fps << " fps";
    }
    // A body due exactly at a frame's end is in that frame (at 2 fps, frame 3 at 1.5 s).
    World world(scene);
    world.PlayAtFixedFrames(0.5f);
    for (int frame = 0; frame < 3; ++frame) world.Advance(0.5f);
    ASSERT_EQ(world.Scene().instances.size(), 1u);
    EXPECT_NEAR(world.Scene().instances[0].Position()[1], 5.0f, 1e-4f);
}

// A deformation's clock is reduced to one period of its motion before the float deformers see
// it: at a phase of 1e6 s a float clock moved in steps of 1/16 s (the wave stood still for
// frames) and the wave's argument lost its shape.
TEST(World, DeformationsKeepMovingAtLargePhases) {
    const LoadedScene scene = ParseScene(R"({
      "models": { "box": { "type": "box" } },
      "instances": [
        { "model": "box", "deform": { "wave": { "amplitude": 0.25, "wavelength": 0.5, "speed": 2,
                                                "phase": 1000000 } } },
        { "model": "box", "deform": { "twist": { "angle": 1, "speed": 3, "phase": -999999 } } } ]
    })",
                                         "deform.json", "");
    World world(scene);
    const double wavePeriod = 0.25, twistPeriod = 2.0 * 3.141592653589793 / 3.0;
    auto reduced = [](double t, double period) { return t - period * std::floor(t / period); };
    for (int frame = 0; frame < 5; ++frame) {
        if (frame > 0) world.Advance(1.0f / 60.0f);
        const double t = frame / 60.0;
        ASSERT_EQ(world.Scene().deformations.size(), 2u);
        EXPECT_NEAR(world.Scene().deformations[0].procedural.time, reduced(1e6 + t, wavePeriod),
                    1e-6)
            << frame;
        EXPECT_NEAR(world.Scene().deformations[1].procedural.time,
                    reduced(-999999.0 + t, twistPeriod), 1e-6)
            << frame;
    }
}

TEST(World, BadDynamicFieldsAreRejected) {
    auto expectError = [](const std::string& json, const std::string& field) {
        try {
            ParseScene(json, "bad.json", "");
            FAIL() << json;
        } catch (const InputError& e) {
            EXPECT_EQ(e.Field(), field) << e.what();
        }
    };
    expectError(R"({"models": {"m": {"type": "teapot", "file": "x"}}, "instances": []})",
                "models.m.file");
    expectError(
        R"({"models": {"b": {"type": "sphere"}}, "instances": [{"model": "b", "animate": {"spin": {}}, "rigid_body": {}}]})",
        "instances[0].rigid_body");
    expectError(
        R"({"models": {"b": {"type": "sphere"}}, "instances": [], "spawners": [{"model": "b"}]})",
        "spawners[0]");
    expectError(
        R"({"models": {"b": {"type": "sphere"}}, "instances": [], "spawners": [{"model": "b", "rain": {"count": 1000, "min": [0, 0, 0], "max": [1, 1, 1]}}]})",
        "spawners[0].rain");
    expectError(
        R"({"models": {"b": {"type": "sphere"}}, "instances": [{"model": "b", "animate": {"spin": {"axis": [0, 0, 0]}}}]})",
        "instances[0].animate.spin.axis");
    // Key times beyond 1e6 s, where a float clip's keys are a second apart.
    expectError(
        R"({"models": {"b": {"type": "sphere"}}, "instances": [{"model": "b", "animate": {"keyframes": {"translation": [[1e7, 0, 0, 0], [10000002, 2, 0, 0]]}}}]})",
        "instances[0].animate.keyframes.translation[0]");
    expectError(
        R"({"instances": [], "camera_path": [{"time": 1, "position": [0, 0, 1], "look_at": [0, 0, 0]}, {"time": 0.5, "position": [0, 0, 1], "look_at": [0, 0, 0]}]})",
        "camera_path[1].time");
}

// Every instance record holds its entity's world transform (the invariant edits must keep).
void ExpectRecordsMatchEntities(World& world) {
    const RenderScene& scene = world.Scene();
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const ecs::Entity e = world.EntityOfInstance(i);
        ASSERT_FALSE(e.IsNull()) << "instance " << i;
        const auto* w = world.Registry().Get<physics::WorldTransform>(e);
        const auto* r = world.Registry().Get<Renderable>(e);
        ASSERT_TRUE(w && r);
        EXPECT_EQ(r->instance, i);
        const Instance expected = MakeInstance(r->blasId, r->materialId, w->objectToWorld);
        for (int row = 0; row < 3; ++row)
            EXPECT_EQ(scene.instances[i].inverseAndPosition.row[row],
                      expected.inverseAndPosition.row[row])
                << i;
    }
}

TEST(WorldEdits, SpawnMoveAndRemoveKeepRecordsInStep) {
    const LoadedScene loaded = ParseScene(kPhysics, "physics.json", "");
    World world(loaded);
    world.Advance(1.0f / 60.0f);
    const size_t before = world.Scene().instances.size();
    EntityDesc desc = loaded.entities[1];  // a ball with its rigid body
    desc.local.translation = vec3(0.0f, 9.0f, 0.0f);
    const ecs::Entity spawned = world.Spawn(desc);
    world.Advance(0.0f);  // what a paused frame loop calls
    ASSERT_EQ(world.Scene().instances.size(), before + 1);
    const uint32_t slot = world.Registry().Get<Renderable>(spawned)->instance;
    EXPECT_EQ(world.EntityOfInstance(slot), spawned);
    // The new record travels to the frame renderer: it is among the changed ones, and the
    // topology changed.
    const SceneChanges changes = world.Changes();
    EXPECT_NE(std::find(changes.instances.begin(), changes.instances.end(), slot),
              changes.instances.end());
    EXPECT_TRUE(changes.topologyChanged);
    EXPECT_EQ(world.Scene().instances[slot].Position()[1], 9.0f);

    // A drag: the body is teleported and stops.
    ASSERT_TRUE(world.SetPose(spawned, vec3(1.0f, 5.0f, -1.0f), glm::identity<glm::quat>()));
    world.Advance(0.0f);
    EXPECT_FALSE(world.Changes().topologyChanged);
    EXPECT_EQ(world.Scene().instances[slot].Position()[0], 1.0f);
    EXPECT_EQ(world.Scene().instances[slot].Position()[1], 5.0f);
    EXPECT_EQ(world.Registry().Get<physics::RigidBody>(spawned)->velocity, vec3(0.0f));
    ExpectRecordsMatchEntities(world);

    // Removing an entity from the middle moves the last record into its slot.
    const ecs::Entity middle = world.EntityOfInstance(3);
    const ecs::Entity last = world.EntityOfInstance(uint32_t(before));
    const std::unique_ptr<FrameRenderer> renderer = MakeFrameRenderer(Backend::kCpu, world.Scene());
    ASSERT_TRUE(world.Remove(middle));
    EXPECT_FALSE(world.Registry().Valid(middle));
    EXPECT_EQ(world.Scene().instances.size(), before);
    EXPECT_EQ(world.EntityOfInstance(3), last);
    world.Advance(1.0f / 60.0f);
    EXPECT_TRUE(world.Changes().topologyChanged);
    renderer->Update(world.Scene(), world.Changes());
    ExpectRecordsMatchEntities(world);
    EXPECT_FALSE(world.Remove(middle));  // already gone
    // The CPU renderer's TLAS was rebuilt over the new set: a ray at the moved record finds it.
    EXPECT_EQ(TlasLeafInstances(renderer->CurrentTlas()).size(), world.Scene().instances.size());
    const Instance& moved = world.Scene().instances[3];
    const vec3 centre(moved.Position()[0], moved.Position()[1], moved.Position()[2]);
    const Ray ray{centre + vec3(0.0f, 0.0f, 50.0f), 1e30f, vec3(0.0f, 0.0f, -1.0f), 0.0f};
    SceneHit hit{};
    ASSERT_TRUE(renderer->Pick(ray, &hit));
    EXPECT_TRUE(hit.instance == 3 ||
                world.Scene().instances[hit.instance].Position()[2] > centre.z);
}

// The window's drag of an animated object lasts: it spins on where it was put (it had snapped
// back to its animation's place the next frame).
TEST(WorldEdits, AnAnimatedObjectMovedByHandStaysWhereItWasPut) {
    const LoadedScene loaded = ParseScene(kAnimated, "animated.json", "");
    World world(loaded);
    world.Advance(1.0f / 60.0f);
    const ecs::Entity ball = world.EntityOfInstance(1);
    ASSERT_NE(world.Registry().Get<physics::Animator>(ball), nullptr);
    const glm::quat turned = world.Registry().Get<physics::LocalTransform>(ball)->rotation;
    ASSERT_TRUE(world.SetPose(ball, vec3(40.0f, 1.0f, 2.0f), turned));
    for (int i = 0; i < 3; ++i) world.Advance(1.0f / 60.0f);
    const auto* local = world.Registry().Get<physics::LocalTransform>(ball);
    EXPECT_EQ(local->translation, vec3(40.0f, 1.0f, 2.0f));
    EXPECT_GT(std::fabs(glm::dot(local->rotation, turned)), 0.99f);  // three frames of spin on
    EXPECT_LT(std::fabs(glm::dot(local->rotation, turned)), 1.0f - 1e-6f);
    ExpectRecordsMatchEntities(world);
}

// Two parent links closed into a cycle in one deferred phase (which SetParent cannot see) no
// longer make RemoveObject walk them for ever: both entities go.
// Deleting the block a ball sleeps on drops the ball: it had stayed asleep in the air, since a
// sleeper wakes only when something near it moves.
TEST(WorldEdits, RemovingWhatASleeperRestsOnWakesIt) {
    const LoadedScene loaded = ParseScene(R"({
      "models": { "floor": { "type": "plane", "size": [20, 0, 20] },
                  "block": { "type": "box", "size": [1, 1, 1] },
                  "ball": { "type": "sphere", "radius": 0.5 } },
      "instances": [ { "model": "floor", "rigid_body": { "static": true } },
                     { "model": "block", "position": [0, 0.5, 0], "rigid_body": { "static": true } },
                     { "model": "ball", "position": [0, 1.5, 0], "rigid_body": {} } ] })",
                                          "sleepers.json", "");
    World world(loaded);
    for (int i = 0; i < 120; ++i) world.Advance(1.0f / 60.0f);
    const ecs::Entity block = world.EntityOfInstance(1), ball = world.EntityOfInstance(2);
    ASSERT_EQ(world.Registry().Get<physics::Collider>(ball)->shape,
              physics::ColliderShape::kSphere);
    ASSERT_TRUE(world.Registry().Get<physics::RigidBody>(ball)->state.sleeping);
    ASSERT_NEAR(world.Registry().Get<physics::LocalTransform>(ball)->translation.y, 1.5f, 0.05f);
    ASSERT_TRUE(world.Remove(block));
    for (int i = 0; i < 120; ++i) world.Advance(1.0f / 60.0f);
    EXPECT_NEAR(world.Registry().Get<physics::LocalTransform>(ball)->translation.y, 0.5f, 0.05f);
}

// A crate dragged out from under a sleeping ball, and a block moved and then deleted before a
// step (both in one frame of the window): the ball falls. A teleported body had not woken what
// slept on it, and the deleted block woke only what was near its new place.
TEST(WorldEdits, DraggingOrMovingThenDeletingWhatASleeperRestsOnWakesIt) {
    constexpr const char* kStack = R"({
      "models": { "floor": { "type": "plane", "size": [20, 0, 20] },
                  "block": { "type": "box", "size": [1, 1, 1] },
                  "ball": { "type": "sphere", "radius": 0.5 } },
      "instances": [ { "model": "floor", "rigid_body": { "static": true } },
                     { "model": "block", "position": [0, 0.5, 0], "rigid_body": { "static": %s } },
                     { "model": "ball", "position": [0, 1.5, 0], "rigid_body": {} } ] })";
    for (const bool moveStaticThenDelete : {false, true}) {
        char json[1024];
        std::snprintf(json, sizeof json, kStack, moveStaticThenDelete ? "true" : "false");
        const LoadedScene loaded = ParseScene(json, "stack.json", "");
        World world(loaded);
        for (int i = 0; i < 180; ++i) world.Advance(1.0f / 60.0f);
        const ecs::Entity block = world.EntityOfInstance(1), ball = world.EntityOfInstance(2);
        ASSERT_TRUE(world.Registry().Get<physics::RigidBody>(ball)->state.sleeping);
        ASSERT_NEAR(world.Registry().Get<physics::LocalTransform>(ball)->translation.y, 1.5f,
                    0.05f);
        ASSERT_TRUE(world.SetPose(block, vec3(6.0f, 0.5f, 0.0f), glm::identity<glm::quat>()));
        if (moveStaticThenDelete) ASSERT_TRUE(world.Remove(block));
        for (int i = 0; i < 120; ++i) world.Advance(1.0f / 60.0f);
        EXPECT_NEAR(world.Registry().Get<physics::LocalTransform>(ball)->translation.y, 0.5f, 0.05f)
            << (moveStaticThenDelete ? "static block moved, then deleted" : "crate dragged away");
    }
}

TEST(WorldEdits, TheObjectRootIsTheTopOfAHierarchy) {
    const LoadedScene loaded = ParseScene(kAnimated, "animated.json", "");
    World world(loaded);
    const ecs::Entity a = world.EntityOfInstance(1), b = world.EntityOfInstance(2);
    EXPECT_EQ(world.ObjectRoot(a), a);
    ASSERT_TRUE(physics::SetParent(world.Registry(), b, a));
    EXPECT_EQ(world.ObjectRoot(b), a);
    ASSERT_TRUE(world.RemoveObject(a));
    EXPECT_TRUE(world.ObjectRoot(b).IsNull());
}

TEST(WorldEdits, RemovingAnObjectWhoseParentsFormACycleEnds) {
    const LoadedScene loaded = ParseScene(kAnimated, "animated.json", "");
    World world(loaded);
    const size_t before = world.Scene().instances.size();
    const ecs::Entity a = world.EntityOfInstance(1), b = world.EntityOfInstance(2);
    {
        const ecs::ScopedDeferral deferral(world.Registry());
        ASSERT_TRUE(physics::SetParent(world.Registry(), a, b));
        ASSERT_TRUE(physics::SetParent(world.Registry(), b, a));
    }
    ASSERT_TRUE(world.RemoveObject(a));
    EXPECT_FALSE(world.Registry().Valid(a));
    EXPECT_FALSE(world.Registry().Valid(b));
    EXPECT_EQ(world.Scene().instances.size(), before - 2);
    world.Advance(1.0f / 60.0f);
    ExpectRecordsMatchEntities(world);
}

}  // namespace
}  // namespace rtrt
