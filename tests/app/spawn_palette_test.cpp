// The window's spawns: every kind lands ahead of the camera, and in a scene with physics it is a
// rigid body thrown along the view.
#include "game/app/spawn_palette.h"

#include <gtest/gtest.h>

#include "engine/render_rt/frame_renderer.h"
#include "engine/render_rt/renderer.h"
#include "game/scene/scene_file.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

constexpr const char* kStatic = R"({
  "camera": { "position": [0, 1, 10], "look_at": [0, 1, 0] },
  "models": { "floor": { "type": "plane", "size": [20, 0, 20] } },
  "instances": [ { "model": "floor" } ]
})";

constexpr const char* kPhysics = R"({
  "camera": { "position": [0, 1, 10], "look_at": [0, 1, 0] },
  "models": { "floor": { "type": "plane", "size": [20, 0, 20] } },
  "instances": [ { "model": "floor", "rigid_body": { "static": true } } ]
})";

TEST(SpawnPalette, KindsLandAheadOfTheCamera) {
    const LoadedScene loaded = ParseScene(kStatic, "static.json", "");
    World world(loaded);
    SpawnPalette palette(world, nullptr);
    ASSERT_NE(palette.Find("sphere"), nullptr);
    ASSERT_NE(palette.Find("glass sphere"), nullptr);
    ASSERT_NE(palette.Find("mirror box"), nullptr);
    EXPECT_GT(world.Scene().materials[palette.Find("glass sphere")->materialId].transmissivity,
              0.0f);
    EXPECT_GT(world.Scene().materials[palette.Find("mirror box")->materialId].reflectivity, 0.8f);
    const Camera& camera = world.Scene().camera;
    for (const SpawnKind& kind : palette.Kinds()) {
        const ecs::Entity e = palette.SpawnInFront(world, kind, camera, 4.0f);
        EXPECT_EQ(world.Registry().Get<physics::RigidBody>(e), nullptr) << kind.name;
        const auto* local = world.Registry().Get<physics::LocalTransform>(e);
        ASSERT_NE(local, nullptr);
        EXPECT_NEAR(local->translation.z, 6.0f, 1e-5f) << kind.name;  // 4 ahead of z = 10
    }
    world.Advance(0.0f);
    EXPECT_EQ(world.Scene().instances.size(), 1 + palette.Kinds().size());
}

// The walker is spawned whole (its skeleton and skinned mesh) and walks: its joint matrices
// change from frame to frame and its deformation is handed on each frame.
TEST(SpawnPalette, SpawnedWalkerWalks) {
    const LoadedScene loaded = ParseScene(kStatic, "static.json", "");
    World world(loaded);
    SpawnPalette palette(world, nullptr);
    const SpawnKind* walker = palette.Find("walker");
    ASSERT_NE(walker, nullptr) << "assets/models/walker.gltf is part of the project";
    palette.SpawnInFront(world, *walker, world.Scene().camera, 4.0f);
    palette.SpawnInFront(world, *walker, world.Scene().camera, 6.0f);
    world.Advance(1.0f / 60.0f);
    ASSERT_EQ(world.Scene().deformations.size(), 2u);
    const std::vector<Affine> before = world.Scene().deformations[0].jointMatrices;
    world.Advance(0.25f);
    EXPECT_EQ(world.Changes().deformations.size(), 2u);
    const std::vector<Affine> after = world.Scene().deformations[0].jointMatrices;
    ASSERT_EQ(before.size(), after.size());
    bool moved = false;
    for (size_t j = 0; j < after.size(); ++j)
        for (int r = 0; r < 3; ++r) moved |= before[j].row[r] != after[j].row[r];
    EXPECT_TRUE(moved);
    // The two copies walk out of step.
    bool apart = false;
    for (size_t j = 0; j < after.size(); ++j)
        for (int r = 0; r < 3; ++r)
            apart |= world.Scene().deformations[1].jointMatrices[j].row[r] != after[j].row[r];
    EXPECT_TRUE(apart);
}

// Deleting a picked walker (its mesh entity) removes the whole character: skeleton, mesh and
// root, and its deformation is free for the next one.
TEST(SpawnPalette, DeletingAPickedWalkerRemovesAllOfIt) {
    const LoadedScene loaded = ParseScene(kStatic, "static.json", "");
    World world(loaded);
    SpawnPalette palette(world, nullptr);
    const SpawnKind* walker = palette.Find("walker");
    ASSERT_NE(walker, nullptr);
    world.Advance(0.0f);
    const size_t entities = world.Registry().Count<physics::LocalTransform>();
    const size_t instances = world.Scene().instances.size();
    palette.SpawnInFront(world, *walker, world.Scene().camera, 4.0f);
    world.Advance(1.0f / 60.0f);
    ASSERT_GT(world.Registry().Count<physics::LocalTransform>(), entities + 10);
    ASSERT_EQ(world.Scene().instances.size(), instances + 1);
    const ecs::Entity mesh = world.EntityOfInstance(uint32_t(instances));  // what a pick gives
    ASSERT_TRUE(world.RemoveObject(mesh));
    world.Advance(1.0f / 60.0f);
    EXPECT_EQ(world.Registry().Count<physics::LocalTransform>(), entities);
    EXPECT_EQ(world.Scene().instances.size(), instances);
    // The next walker takes the freed deformation rather than a new one.
    palette.SpawnInFront(world, *walker, world.Scene().camera, 4.0f);
    world.Advance(1.0f / 60.0f);
    EXPECT_EQ(world.Scene().deformations.size(), 1u);
}

// A pick of a walker's mesh selects the whole walker (its root): moving that moves what is seen,
// where the mesh node moved alone had left the skinned walker where it was.
TEST(SpawnPalette, APickedWalkerMovesWhole) {
    const LoadedScene loaded = ParseScene(kStatic, "static.json", "");
    World world(loaded);
    SpawnPalette palette(world, nullptr);
    const SpawnKind* walker = palette.Find("walker");
    ASSERT_NE(walker, nullptr);
    world.Advance(0.0f);
    const uint32_t instance = uint32_t(world.Scene().instances.size());
    const vec3 ground(1.0f, -2.0f, 3.0f);  // what the window finds below the view's centre
    const ecs::Entity spawned =
        palette.SpawnInFront(world, *walker, world.Scene().camera, 4.0f, &ground);
    world.Advance(1.0f / 60.0f);
    const ecs::Entity root = world.ObjectRoot(world.EntityOfInstance(instance));
    EXPECT_EQ(root, spawned);
    EXPECT_EQ(world.Registry().Get<physics::LocalTransform>(root)->translation, ground);
    const vec3 placed = world.Scene().instances[instance].Position();
    ASSERT_TRUE(world.SetPose(root, ground + vec3(5.0f, 0.0f, 0.0f),
                              world.Registry().Get<physics::LocalTransform>(root)->rotation));
    world.Advance(0.0f);
    EXPECT_NEAR(world.Scene().instances[instance].Position().x, placed.x + 5.0f, 1e-4f);
}

// A flat model rests on the ground: its collider is a box around it (a sphere of its largest
// half extent had held the teapot 0.2 above the floor).
TEST(SpawnPalette, ModelCollidersHoldTheirModels) {
    const LoadedScene loaded = ParseScene(kPhysics, "physics.json", "");
    World world(loaded);
    SpawnPalette palette(world, nullptr);
    for (const char* name : {"teapot", "dragon"}) {
        const SpawnKind* kind = palette.Find(name);
        if (!kind) continue;  // its model was not fetched
        const Aabb bounds = world.Scene().blases[kind->blasId]->bounds;
        ASSERT_EQ(kind->collider.shape, physics::ColliderShape::kBox) << name;
        EXPECT_NEAR(kind->collider.halfExtents.y, 0.5f * bounds.Extent().y, 1e-4f) << name;
        EXPECT_NEAR(kind->collider.halfExtents.x, 0.5f * bounds.Extent().x, 1e-4f) << name;
    }
}

// Where a character stands: on the floor below the point ahead, the view looking through a
// dynamic ball in its centre (a character put on a falling ball was left in the air); and at
// least 2 ahead of a low camera looking down, which had stood it in the camera.
TEST(SpawnPalette, ACharacterStandsOnStillGroundAhead) {
    const LoadedScene loaded = ParseScene(R"({
      "camera": { "position": [0, 1, 10], "look_at": [0, 1, 0] },
      "models": { "floor": { "type": "plane", "size": [40, 0, 40] },
                  "ball": { "type": "sphere", "radius": 0.5 } },
      "instances": [ { "model": "floor", "rigid_body": { "static": true } },
                     { "model": "ball", "position": [0, 1, 0], "rigid_body": {} } ] })",
                                          "ground.json", "");
    World world(loaded);
    const std::unique_ptr<FrameRenderer> renderer = MakeFrameRenderer(Backend::kCpu, world.Scene());
    const ScenePick pick = [&](const Ray& ray, SceneHit* hit) { return renderer->Pick(ray, hit); };
    const std::optional<vec3> ahead = SpawnGround(world, world.Scene().camera, 4.0f, pick);
    ASSERT_TRUE(ahead.has_value());
    EXPECT_NEAR(ahead->x, 0.0f, 1e-4f);
    EXPECT_NEAR(ahead->y, 0.0f, 1e-4f);
    EXPECT_NEAR(ahead->z, 6.0f, 1e-4f);  // 4 ahead, below; the ball is looked through

    Camera low = world.Scene().camera;
    low.position = vec3(0.0f, 0.4f, 10.0f);
    low.forward = glm::normalize(vec3(0.0f, -0.4f, -0.2f));
    const std::optional<vec3> below = SpawnGround(world, low, 4.0f, pick);
    ASSERT_TRUE(below.has_value());
    EXPECT_NEAR(below->y, 0.0f, 1e-4f);
    EXPECT_NEAR(below->z, 8.0f, 1e-4f);  // 2 ahead across the ground
}

TEST(SpawnPalette, WithPhysicsSpawnsAreThrown) {
    const LoadedScene loaded = ParseScene(kPhysics, "physics.json", "");
    World world(loaded);
    ASSERT_TRUE(world.HasPhysics());
    SpawnPalette palette(world, nullptr);
    const ecs::Entity e =
        palette.SpawnInFront(world, *palette.Find("sphere"), world.Scene().camera, 4.0f);
    const auto* body = world.Registry().Get<physics::RigidBody>(e);
    ASSERT_NE(body, nullptr);
    EXPECT_NEAR(body->velocity.z, -SpawnPalette::kThrowSpeed, 1e-5f);
    ASSERT_NE(world.Registry().Get<physics::Collider>(e), nullptr);
    // It flies forward (and falls): after half a second it is further along -z.
    for (int i = 0; i < 30; ++i) world.Advance(1.0f / 60.0f);
    EXPECT_LT(world.Registry().Get<physics::LocalTransform>(e)->translation.z, 4.0f);
}

}  // namespace
}  // namespace rtrt
