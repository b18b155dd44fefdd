// Rigid bodies: resting contact, energy, tunnelling, determinism, sleeping, the fixed step and
// its interpolation, and the cost of a scene without bodies.
#include "engine/physics_anim/physics_world.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "engine/core/timer.h"
#include "engine/physics_anim/physics_anim_systems.h"
#include "engine/physics_anim/random_spawn.h"
#include "engine/physics_anim/stage_runner.h"
#include "tests/physics_anim/pile.h"

namespace rtrt::physics {
namespace {

using ecs::Entity;
using ecs::Registry;
using test::AddPit;
using test::AddPlane;
using test::PileResult;
using test::RunPile;

constexpr float kStep = 1.0f / 120.0f;

Entity AddBody(Registry& registry, vec3 position, Collider collider, float mass,
               vec3 velocity = vec3(0.0f), float restitution = 0.0f,
               glm::quat rotation = glm::identity<glm::quat>()) {
    const Entity e = registry.Create();
    LocalTransform local;
    local.translation = position;
    local.rotation = rotation;
    registry.Add(e, local);
    RigidBody body;
    body.mass = mass;
    body.velocity = velocity;
    body.restitution = restitution;
    registry.Add(e, body);
    registry.Add(e, collider);
    return e;
}

vec3 Position(const Registry& registry, Entity e) {
    return registry.Get<RigidBody>(e)->state.position;
}

TEST(PhysicsWorldTest, SphereAndBoxRestingOnAPlaneStayAtRestForTenSeconds) {
    Registry registry;
    AddPlane(registry, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    const vec3 sphereStart(0.0f, 0.5f, 0.0f);
    const vec3 boxStart(3.0f, 0.25f, 1.0f);
    const Entity sphere = AddBody(registry, sphereStart, Collider::Sphere(0.5f), 2.0f);
    const Entity box = AddBody(registry, boxStart, Collider::Box(vec3(0.6f, 0.25f, 0.4f)), 5.0f,
                               vec3(0.0f), 0.0f, glm::angleAxis(0.4f, vec3(0.0f, 1.0f, 0.0f)));
    PhysicsWorld world;
    float maxDrift = 0.0f;
    for (int step = 0; step < 1200; ++step) {
        world.Step(registry);
        maxDrift = std::max({maxDrift, glm::length(Position(registry, sphere) - sphereStart),
                             glm::length(Position(registry, box) - boxStart)});
    }
    EXPECT_LT(maxDrift, 1e-4f);
    EXPECT_TRUE(registry.Get<RigidBody>(sphere)->state.sleeping);
    EXPECT_TRUE(registry.Get<RigidBody>(box)->state.sleeping);
}

TEST(PhysicsWorldTest, BoxStackedOnABoxStaysAtRest) {
    Registry registry;
    AddPlane(registry, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    const vec3 bottomStart(0.0f, 0.5f, 0.0f);
    const vec3 topStart(0.1f, 1.25f, -0.05f);
    const Entity bottom = AddBody(registry, bottomStart, Collider::Box(vec3(0.5f)), 4.0f);
    const Entity top = AddBody(registry, topStart, Collider::Box(vec3(0.3f, 0.25f, 0.3f)), 1.0f);
    PhysicsWorld world;
    float maxDrift = 0.0f;
    for (int step = 0; step < 1200; ++step) {
        world.Step(registry);
        maxDrift = std::max({maxDrift, glm::length(Position(registry, bottom) - bottomStart),
                             glm::length(Position(registry, top) - topStart)});
    }
    EXPECT_LT(maxDrift, 1e-4f);
    EXPECT_TRUE(registry.Get<RigidBody>(top)->state.sleeping);
}

TEST(PhysicsWorldTest, DroppedBodiesSettleOnTheFloor) {
    Registry registry;
    AddPlane(registry, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    const Entity sphere =
        AddBody(registry, vec3(0.0f, 2.0f, 0.0f), Collider::Sphere(0.3f), 1.0f, vec3(0.0f), 0.6f);
    const glm::quat tilt = glm::normalize(glm::quat(0.9f, 0.3f, 0.2f, -0.1f));
    const Entity box = AddBody(registry, vec3(3.0f, 2.0f, 0.0f),
                               Collider::Box(vec3(0.5f, 0.2f, 0.3f)), 1.0f, vec3(0.0f), 0.2f, tilt);
    PhysicsWorld world;
    world.Step(registry, 8 * 120);
    const RigidBody& s = *registry.Get<RigidBody>(sphere);
    EXPECT_NEAR(s.state.position.y, 0.3f, 2e-3f);
    EXPECT_TRUE(s.state.sleeping);
    const RigidBody& b = *registry.Get<RigidBody>(box);
    EXPECT_TRUE(b.state.sleeping);
    // Lying on its largest face: the lowest corner on the floor, the centre at the half height.
    EXPECT_NEAR(b.state.position.y, 0.2f, 2e-3f);
    const vec3 up = b.state.orientation * vec3(0.0f, 1.0f, 0.0f);
    EXPECT_GT(std::fabs(up.y), 0.999f);
}

double TotalEnergy(const PhysicsWorld& world, const Registry& registry) {
    return world.MechanicalEnergy(registry);
}

// Restitution up to 1, friction, sphere-sphere and sphere-plane contacts: the total mechanical
// energy may only fall. Tolerance per step: 1e-6 of the starting energy, which covers float
// rounding of positions and velocities (about 1e-7 relative each) summed over the bodies.
TEST(PhysicsWorldTest, EnergyNeverGrowsInABouncingPileOfSpheres) {
    Registry registry;
    AddPit(registry, 1.5f);
    SpawnDesc desc;
    desc.count = 200;
    desc.regionMin = vec3(-1.5f, 0.0f, -1.5f);
    desc.regionMax = vec3(1.5f, 6.0f, 1.5f);
    desc.minSize = 0.08f;
    desc.maxSize = 0.15f;
    desc.maxSpeed = 3.0f;
    desc.minRestitution = 0.5f;
    desc.maxRestitution = 1.0f;
    desc.friction = 0.4f;
    ASSERT_EQ(SpawnRandomBodies(registry, desc, 7).size(), 200u);
    // Some bodies bounce perfectly.
    int elastic = 0;
    registry.View<RigidBody>().Each([&](Entity, RigidBody& body) {
        if (body.mass > 0.0f && (elastic++ % 4) == 0) body.restitution = 1.0f;
    });

    PhysicsWorld world;
    const double start = TotalEnergy(world, registry);
    const double tolerance = 1e-6 * std::fabs(start);
    double previous = start;
    double worstGrowth = -1e300;
    uint64_t contacts = 0;
    for (int step = 0; step < 6 * 120; ++step) {
        world.Step(registry);
        contacts += world.Stats().lastContacts;
        const double energy = TotalEnergy(world, registry);
        worstGrowth = std::max(worstGrowth, energy - previous);
        ASSERT_LE(energy, previous + tolerance) << "step " << step;
        previous = energy;
    }
    EXPECT_GT(contacts, 10000u);  // the spheres did meet each other and the pit
    EXPECT_LT(previous, 0.9 * start);
    RecordProperty("worst_growth_per_step_j", std::to_string(worstGrowth));
}

// A lone elastic ball keeps most of its energy: the bounce loses only one step of gravity.
TEST(PhysicsWorldTest, ElasticBallBouncesBackNearlyToItsHeight) {
    Registry registry;
    AddPlane(registry, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    const Entity ball =
        AddBody(registry, vec3(0.0f, 2.0f, 0.0f), Collider::Sphere(0.1f), 1.0f, vec3(0.0f), 1.0f);
    PhysicsWorld world;
    float highest = 0.0f;
    bool bounced = false;
    for (int step = 0; step < 180; ++step) {  // the first bounce is at 0.6 s, the apex at 1.2 s
        world.Step(registry);
        const RigidBody& b = *registry.Get<RigidBody>(ball);
        if (b.velocity.y > 0.0f) bounced = true;
        if (bounced) highest = std::max(highest, b.state.position.y);
    }
    EXPECT_TRUE(bounced);
    EXPECT_LE(highest, 2.0f);
    EXPECT_GT(highest, 1.85f);
}

struct ShotResult {
    float lowest;  // of the sphere's centre over all steps
    float finalHeight;
};

ShotResult FireAtFloor(vec3 direction, float speed, bool thinBoxFloor) {
    Registry registry;
    constexpr float kRadius = 0.02f;
    if (thinBoxFloor) {
        // Wide enough that the ball, skidding on at up to 140 m/s, is still over it at the end.
        AddBody(registry, vec3(0.0f, -0.005f, 0.0f), Collider::Box(vec3(500.0f, 0.005f, 500.0f)),
                0.0f);
    } else {
        AddPlane(registry, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    }
    const Entity ball = AddBody(registry, vec3(0.0f, 7.0f, 0.0f), Collider::Sphere(kRadius), 0.01f,
                                speed * glm::normalize(direction), 0.0f);
    PhysicsWorld world;
    ShotResult result{kInfinity, 0.0f};
    for (int step = 0; step < 60; ++step) {
        world.Step(registry);
        result.lowest = std::min(result.lowest, Position(registry, ball).y);
    }
    result.finalHeight = Position(registry, ball).y;
    return result;
}

// The documented limit (PhysicsSettings::maxLinearSpeed, 200 m/s, 1.67 m per 1/120 s step, 42
// times the 0.04 m diameter of the ball): fired straight down and at an angle, into a plane and
// into a 1 cm thick box, the ball never gets more than 0.1 mm into the floor.
TEST(PhysicsWorldTest, NoTunnellingAtTheMaximumSpeed) {
    const float maxSpeed = PhysicsSettings{}.maxLinearSpeed;
    ASSERT_EQ(maxSpeed, 200.0f);
    for (const bool thinBox : {false, true}) {
        for (const vec3 direction : {vec3(0.0f, -1.0f, 0.0f), vec3(1.0f, -1.0f, 0.3f)}) {
            const ShotResult shot = FireAtFloor(direction, maxSpeed, thinBox);
            EXPECT_GE(shot.lowest, 0.02f - 1e-4f) << "thin box " << thinBox;
            EXPECT_NEAR(shot.finalHeight, 0.02f, 2e-3f) << "thin box " << thinBox;
        }
    }
}

// Faster bodies are clamped to the limit, so they do not tunnel either.
TEST(PhysicsWorldTest, SpeedsAboveTheLimitAreClamped) {
    const ShotResult shot = FireAtFloor(vec3(0.0f, -1.0f, 0.0f), 5000.0f, true);
    EXPECT_GE(shot.lowest, 0.02f - 1e-4f);
    Registry registry;
    const Entity e =
        AddBody(registry, vec3(0.0f), Collider::Sphere(0.1f), 1.0f, vec3(0.0f, 0.0f, 1000.0f));
    PhysicsWorld world;
    world.Step(registry);
    EXPECT_NEAR(glm::length(registry.Get<RigidBody>(e)->velocity), 200.0f, 1e-3f);
}

std::vector<float> RunSeeded(uint64_t seed, int steps) {
    SpawnDesc desc;
    desc.count = 300;
    desc.regionMin = vec3(-3.0f, 0.0f, -3.0f);
    desc.regionMax = vec3(3.0f, 6.0f, 3.0f);
    desc.maxSize = 0.2f;
    desc.boxFraction = 0.3f;
    desc.maxSpeed = 2.0f;
    desc.minRestitution = 0.1f;
    desc.maxRestitution = 0.8f;
    return RunPile(desc, seed, {.steps = steps}).state;
}

TEST(PhysicsWorldTest, SameSeedGivesBitIdenticalResults) {
    const std::vector<float> a = RunSeeded(42, 480);
    const std::vector<float> b = RunSeeded(42, 480);
    ASSERT_EQ(a.size(), 300u * 13u);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
    EXPECT_NE(RunSeeded(43, 480), a);
}

// Spheres and boxes of 0.1-0.2 m rained over the whole 6 m pit, up to 8 m high (it holds about
// 700 of them).
SpawnDesc MixedPile(uint32_t count) {
    SpawnDesc desc;
    desc.count = count;
    desc.regionMin = vec3(-3.0f, 0.0f, -3.0f);
    desc.regionMax = vec3(3.0f, 8.0f, 3.0f);
    desc.minSize = 0.1f;
    desc.maxSize = 0.2f;
    desc.boxFraction = 0.3f;
    return desc;
}

// The solver runs a colour's manifolds in parallel: the same pile on 1, 3 and 8 threads must give
// the same bits, velocities included.
PileResult RunOnThreads(int threads) {
    SpawnDesc desc = MixedPile(1500);
    desc.maxSpeed = 2.0f;
    return RunPile(desc, 7, {.threads = threads});
}

TEST(PhysicsWorldTest, SameBitsOnAnyNumberOfThreads) {
    const PileResult one = RunOnThreads(1);
    // A settled pile: enough manifolds per colour that a colour is split among threads.
    EXPECT_GE(one.colors, 4u);
    EXPECT_GT(one.contacts, 1500u);
    for (const int threads : {3, 8}) {
        const PileResult many = RunOnThreads(threads);
        ASSERT_EQ(many.state.size(), one.state.size());
        EXPECT_EQ(
            std::memcmp(many.state.data(), one.state.data(), one.state.size() * sizeof(float)), 0)
            << threads << " threads";
        EXPECT_EQ(many.colors, one.colors);
        EXPECT_EQ(many.contacts, one.contacts);
    }
}

// A world of fewer than minParallelBodies bodies steps on one thread whatever TBB lends, with the
// bits of any other number; a larger one uses every thread it is lent.
TEST(PhysicsWorldTest, SmallWorldStepsOnOneThread) {
    const SpawnDesc desc = MixedPile(300);
    const uint32_t cut = PhysicsSettings{}.minParallelBodies;
    const PileResult one = RunPile(desc, 5, {.steps = 60, .threads = 1, .minParallelBodies = cut});
    const PileResult four = RunPile(desc, 5, {.steps = 60, .threads = 4, .minParallelBodies = cut});
    ASSERT_LT(one.state.size() / 13 + 5, cut);  // the bodies and the pit's five planes
    EXPECT_EQ(one.threads, 1u);
    EXPECT_EQ(four.threads, 1u);
    EXPECT_EQ(four.state, one.state);
    // The same world with a lower cut: every thread the arena lends.
    const uint32_t lent = static_cast<uint32_t>(
        tbb::task_arena(4).execute([] { return StageRunner::AvailableThreads(); }));
    const PileResult low = RunPile(desc, 5, {.steps = 60, .threads = 4, .minParallelBodies = 100});
    EXPECT_EQ(low.threads, lent);
    EXPECT_EQ(low.state, one.state);
}

TEST(PhysicsWorldTest, ZeroBodiesDoNoWork) {
    Registry registry;
    for (int i = 0; i < 10000; ++i)
        registry.Add(registry.Create(), LocalTransform{vec3(static_cast<float>(i))});
    registry.ClearChanged<LocalTransform>();
    PhysicsWorld world;
    const Stopwatch clock;
    for (int frame = 0; frame < 10000; ++frame) world.Advance(registry, 1.0f / 60.0f);
    const double ms = clock.Milliseconds();
    EXPECT_EQ(world.Stats().frames, 0u);
    EXPECT_EQ(world.Stats().steps, 0u);
    EXPECT_EQ(world.Stats().bodySteps, 0u);
    EXPECT_EQ(registry.ChangedCount<LocalTransform>(), 0u);
    EXPECT_LT(ms, 5.0);  // 10,000 frames: a pool-size check each
    // One body is enough to make it work.
    AddBody(registry, vec3(0.0f, 5.0f, 0.0f), Collider::Sphere(0.5f), 1.0f);
    world.Advance(registry, 1.0f / 60.0f);
    EXPECT_EQ(world.Stats().frames, 1u);
    EXPECT_EQ(world.Stats().steps, 2u);
    EXPECT_EQ(world.Stats().bodySteps, 2u);
}

TEST(PhysicsWorldTest, AccumulatorTakesWholeStepsAndInterpolatesTheRest) {
    Registry registry;
    const Entity ball = AddBody(registry, vec3(0.0f, 10.0f, 0.0f), Collider::Sphere(0.5f), 1.0f,
                                vec3(1.0f, 0.0f, 0.0f));
    PhysicsWorld world;
    world.Advance(registry, 2.5f * kStep);
    EXPECT_EQ(world.Stats().steps, 2u);
    EXPECT_NEAR(world.InterpolationAlpha(), 0.5f, 1e-4f);
    const RigidBody::State& s = registry.Get<RigidBody>(ball)->state;
    const vec3 expected = glm::mix(s.previousPosition, s.position, world.InterpolationAlpha());
    EXPECT_EQ(registry.Get<LocalTransform>(ball)->translation, expected);
    // Symplectic Euler: x after two steps is x0 + h (v + g h) + h (v + 2 g h).
    EXPECT_NEAR(s.position.x, 2.0f * kStep, 1e-6f);
    EXPECT_NEAR(s.position.y, 10.0f - 3.0f * 9.81f * kStep * kStep, 1e-5f);

    world.Advance(registry, 0.25f * kStep);
    EXPECT_EQ(world.Stats().steps, 2u);  // still no whole step due
    EXPECT_NEAR(world.InterpolationAlpha(), 0.75f, 1e-4f);

    world.Advance(registry, 1.0f);  // a long frame runs at most maxStepsPerFrame steps
    EXPECT_EQ(world.Stats().steps, 2u + 8u);
    EXPECT_LT(world.InterpolationAlpha(), 1.0f);
}

// An offline player's frames of 1/5 s each take every step their time holds: the real-time cap
// of 8 steps a frame had run them at a third of the speed.
TEST(PhysicsWorldTest, FixedLongFramesKeepUp) {
    Registry registry;
    const Entity ball = AddBody(registry, vec3(0.0f, 100.0f, 0.0f), Collider::Sphere(0.5f), 1.0f);
    PhysicsWorld world;
    world.KeepUpWithFrames(0.2f);
    for (int frame = 0; frame < 5; ++frame) world.Advance(registry, 0.2f);
    EXPECT_GE(world.Stats().steps, 119u);
    EXPECT_LE(world.Stats().steps, 120u);
    // A second of free fall: 100 - g / 2 within the symplectic step's error.
    EXPECT_NEAR(registry.Get<LocalTransform>(ball)->translation.y, 100.0f - 0.5f * 9.81f, 0.1f);
}

TEST(PhysicsWorldTest, SleepingBodyWakesWhenHitOrPushed) {
    Registry registry;
    AddPlane(registry, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    const Entity sleeper = AddBody(registry, vec3(0.0f, 0.5f, 0.0f), Collider::Sphere(0.5f), 1.0f);
    PhysicsWorld world;
    world.Step(registry, 120);
    ASSERT_TRUE(registry.Get<RigidBody>(sleeper)->state.sleeping);
    EXPECT_EQ(world.Stats().lastAwake, 0u);

    const Entity hammer = AddBody(registry, vec3(0.3f, 3.0f, 0.0f), Collider::Sphere(0.5f), 5.0f);
    world.Step(registry, 120);
    EXPECT_FALSE(registry.Get<RigidBody>(sleeper)->state.sleeping);
    EXPECT_GT(std::fabs(Position(registry, sleeper).x), 0.01f);  // knocked sideways
    world.Step(registry, 20 * 120);
    EXPECT_TRUE(registry.Get<RigidBody>(sleeper)->state.sleeping);
    EXPECT_TRUE(registry.Get<RigidBody>(hammer)->state.sleeping);

    registry.Get<RigidBody>(sleeper)->velocity = vec3(0.0f, 3.0f, 0.0f);
    world.Step(registry);
    EXPECT_FALSE(registry.Get<RigidBody>(sleeper)->state.sleeping);
    EXPECT_GT(Position(registry, sleeper).y, 0.5f);
}

// A static body placed into a sleeper (spawned later), or moved into one, wakes it, and the
// sleeper is pushed out: static bodies never count as awake, so it had stayed inside for good.
TEST(PhysicsWorldTest, StaticBodyPlacedOrMovedIntoASleeperWakesIt) {
    Registry registry;
    AddPlane(registry, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    const Entity sleeper = AddBody(registry, vec3(0.0f, 0.5f, 0.0f), Collider::Sphere(0.5f), 1.0f);
    PhysicsWorld world;
    world.Step(registry, 240);
    ASSERT_TRUE(registry.Get<RigidBody>(sleeper)->state.sleeping);
    const Entity block = AddBody(registry, vec3(0.0f, 0.3f, 0.0f), Collider::Box(vec3(0.5f)), 0.0f);
    world.Step(registry, 240);
    EXPECT_GT(Position(registry, sleeper).y, 1.3f - 0.05f);  // on top of the block (top 0.8)
    // Asleep on the block, it is pushed out again when the block is moved into it.
    world.Step(registry, 20 * 120);
    ASSERT_TRUE(registry.Get<RigidBody>(sleeper)->state.sleeping);
    const float before = Position(registry, sleeper).y;
    registry.Get<LocalTransform>(block)->translation = vec3(0.0f, 0.8f, 0.0f);
    world.Step(registry, 240);
    EXPECT_GT(Position(registry, sleeper).y, before + 0.45f);
    // A plane placed under it later (outside the broad phase) wakes it too.
    world.Step(registry, 20 * 120);
    ASSERT_TRUE(registry.Get<RigidBody>(sleeper)->state.sleeping);
    const float onBlock = Position(registry, sleeper).y;
    AddPlane(registry, vec3(0.0f, onBlock, 0.0f), vec3(0.0f, 1.0f, 0.0f));
    world.Step(registry, 240);
    EXPECT_GT(Position(registry, sleeper).y, onBlock + 0.4f);
}

// A static body or plane moved away from under sleepers wakes them, and they fall: they had stayed
// asleep in the air where it was, since only bodies near where it now is were woken.
TEST(PhysicsWorldTest, StaticBodyOrPlaneMovedAwayFromSleepersWakesThem) {
    Registry registry;
    const Entity floor = AddPlane(registry, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    const Entity block = AddBody(registry, vec3(0.0f, 0.5f, 0.0f), Collider::Box(vec3(0.5f)), 0.0f);
    const Entity sleeper = AddBody(registry, vec3(0.0f, 1.5f, 0.0f), Collider::Sphere(0.5f), 1.0f);
    PhysicsWorld world;
    world.Step(registry, 20 * 120);
    ASSERT_TRUE(registry.Get<RigidBody>(sleeper)->state.sleeping);
    ASSERT_NEAR(Position(registry, sleeper).y, 1.5f, 0.05f);
    registry.Get<LocalTransform>(block)->translation = vec3(5.0f, 0.5f, 0.0f);
    world.Step(registry, 240);
    EXPECT_NEAR(Position(registry, sleeper).y, 0.5f, 0.05f);  // on the floor
    EXPECT_NEAR(Position(registry, sleeper).x, 0.0f, 0.05f);  // straight down

    world.Step(registry, 20 * 120);
    ASSERT_TRUE(registry.Get<RigidBody>(sleeper)->state.sleeping);
    registry.Get<LocalTransform>(floor)->translation = vec3(0.0f, -2.0f, 0.0f);
    world.Step(registry, 240);
    EXPECT_NEAR(Position(registry, sleeper).y, -1.5f, 0.05f);  // on the lowered floor
}

// A plane's normal is in its body's frame, turned by the body's rotation like every collider.
TEST(PhysicsWorldTest, RotatedPlanesAreWallsAndRamps) {
    Registry registry;
    AddPlane(registry, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    // A wall at x = 3 facing -x: the floor's plane turned 90 degrees about z.
    const Entity wall = registry.Create();
    LocalTransform wallPose;
    wallPose.translation = vec3(3.0f, 0.0f, 0.0f);
    wallPose.rotation = glm::angleAxis(glm::radians(90.0f), vec3(0.0f, 0.0f, 1.0f));
    registry.Add(wall, wallPose);
    RigidBody wallBody;
    wallBody.mass = 0.0f;
    registry.Add(wall, wallBody);
    registry.Add(wall, Collider::Plane(vec3(0.0f, 1.0f, 0.0f)));
    const Entity faller = AddBody(registry, vec3(0.0f, 3.0f, 0.0f), Collider::Sphere(0.5f), 1.0f);
    const Entity thrown =
        AddBody(registry, vec3(1.0f, 0.5f, 1.0f), Collider::Sphere(0.5f), 1.0f, vec3(8.0f, 0, 0));
    PhysicsWorld world;
    float maxX = 0.0f;
    for (int step = 0; step < 360; ++step) {
        world.Step(registry);
        maxX = std::max(maxX, Position(registry, thrown).x);
    }
    EXPECT_NEAR(Position(registry, faller).y, 0.5f, 0.02f);  // on the floor, not under it
    EXPECT_LT(maxX, 2.5f + 0.05f);                           // stopped by the wall
    EXPECT_GT(maxX, 2.4f);
}

TEST(PhysicsWorldTest, OnlyMovingBodiesMarkTheirTransformsChanged) {
    Registry registry;
    AddPlane(registry, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    const Entity resting = AddBody(registry, vec3(0.0f, 0.5f, 0.0f), Collider::Sphere(0.5f), 1.0f);
    PhysicsWorld world;
    world.Step(registry, 120);  // the resting ball falls asleep
    const Entity falling = AddBody(registry, vec3(3.0f, 5.0f, 0.0f), Collider::Sphere(0.5f), 1.0f);
    registry.ClearChanged<LocalTransform>();
    world.Advance(registry, 1.0f / 60.0f);
    ASSERT_EQ(registry.ChangedCount<LocalTransform>(), 1u);
    registry.EachChanged<LocalTransform>([&](Entity e, LocalTransform&) { EXPECT_EQ(e, falling); });
    EXPECT_TRUE(registry.Get<RigidBody>(resting)->state.sleeping);
}

// In the scheduler: physics moves the ball in "simulation", the transform system turns that into
// a world transform in "animation"; the static ground's world transform is written once.
TEST(PhysicsWorldTest, SchedulerFrameMovesOnlyTheDynamicBodysWorldTransform) {
    Registry registry;
    ecs::Scheduler scheduler;
    PhysicsWorld physics;
    TransformSystem transforms;
    AddPhysicsAnimSystems(scheduler, physics, transforms);
    const Entity ground = AddPlane(registry, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    const Entity ball = AddBody(registry, vec3(0.0f, 5.0f, 0.0f), Collider::Sphere(0.5f), 1.0f);
    scheduler.RunFrame(registry, 1.0f / 60.0f);
    EXPECT_EQ(registry.ChangedCount<WorldTransform>(), 2u);  // both appear
    registry.ClearChanged<WorldTransform>();
    for (int frame = 0; frame < 30; ++frame) {
        scheduler.RunFrame(registry, 1.0f / 60.0f);
        ASSERT_EQ(registry.ChangedCount<WorldTransform>(), 1u);
        registry.EachChanged<WorldTransform>(
            [&](Entity e, WorldTransform&) { EXPECT_EQ(e, ball); });
        registry.ClearChanged<WorldTransform>();
    }
    EXPECT_EQ(physics.Stats().steps, 62u);
    EXPECT_EQ(vec3(registry.Get<WorldTransform>(ball)->objectToWorld[3]),
              registry.Get<LocalTransform>(ball)->translation);
    EXPECT_LT(registry.Get<LocalTransform>(ball)->translation.y, 5.0f - 0.5f * 9.81f * 0.25f);
    EXPECT_EQ(vec3(registry.Get<WorldTransform>(ground)->objectToWorld[3]), vec3(0.0f));
}

// Real time: 2,000 bodies (a fifth of them boxes) falling into a pit and piling up; the mean
// step must fit the 1/120 s it simulates with room to spare.
// A large pile steps and keeps its contacts. Its speed is reported, not asserted: timings belong to
// benchmarks (rtrt bench runtime / frame), and a loaded CI machine would make an assertion flaky.
TEST(PhysicsWorldTest, TwoThousandBodiesPileUp) {
    Registry registry;
    AddPit(registry, 4.0f);
    SpawnDesc desc;
    desc.count = 2000;
    desc.regionMin = vec3(-4.0f, 0.0f, -4.0f);
    desc.regionMax = vec3(4.0f, 12.0f, 4.0f);
    desc.minSize = 0.1f;
    desc.maxSize = 0.18f;
    desc.boxFraction = 0.2f;
    desc.maxSpeed = 1.0f;
    ASSERT_EQ(SpawnRandomBodies(registry, desc, 1).size(), 2000u);
    PhysicsWorld world;
    const Stopwatch clock;
    constexpr int kSteps = 240;
    uint64_t contacts = 0;
    for (int i = 0; i < kSteps; ++i) {
        world.Step(registry);
        contacts += world.Stats().lastContacts;
    }
    const double msPerStep = clock.Milliseconds() / kSteps;
    RecordProperty("ms_per_step", std::to_string(msPerStep));
    std::printf("2000 bodies: %.3f ms per step, %.0f contacts per step\n", msPerStep,
                static_cast<double>(contacts) / kSteps);
    EXPECT_GT(contacts, 2000u * 60u);
}

}  // namespace
}  // namespace rtrt::physics
