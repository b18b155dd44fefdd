// The GPU contact solver against the CPU one: the same piles, stepped with contacts solved on the
// CPU's threads and on the GPU, must end with every body's every float equal (gpu_contact_solver.h
// says why they can). Skipped without a CUDA device.
#include "engine/physics_anim/gpu_contact_solver.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/physics_anim/physics_world.h"
#include "engine/physics_anim/random_spawn.h"
#include "tests/physics_anim/pile.h"

namespace rtrt::physics {
namespace {

using ecs::Entity;
using ecs::Registry;
using test::PileResult;
using test::RunPile;

constexpr uint64_t kSeed = 11;

bool HaveGpuSolver(std::string* why) { return GpuContactSolver::Create(why) != nullptr; }

void ExpectSameBits(const PileResult& cpu, const PileResult& gpu) {
    ASSERT_EQ(gpu.state.size(), cpu.state.size());
    size_t firstDifference = cpu.state.size();
    for (size_t i = 0; i < cpu.state.size(); ++i) {
        // Equal values: a zero's sign may differ (gpu_contact_solver.h says where).
        if (!(cpu.state[i] == gpu.state[i])) {
            firstDifference = i;
            break;
        }
    }
    EXPECT_EQ(firstDifference, cpu.state.size())
        << "body " << firstDifference / 13 << " field " << firstDifference % 13 << ": cpu "
        << cpu.state[firstDifference] << ", gpu " << gpu.state[firstDifference];
    EXPECT_EQ(gpu.contacts, cpu.contacts);
    EXPECT_EQ(gpu.colors, cpu.colors);
}

// Spheres and boxes of mixed sizes, bouncing and rolling: every pass of the solver (warm start,
// friction, rolling resistance, restitution, split impulse) does work.
TEST(GpuContactSolverTest, MixedPileGivesTheCpuSolversResult) {
    std::string why;
    if (!HaveGpuSolver(&why)) GTEST_SKIP() << why;
    SpawnDesc desc;
    desc.count = 1500;
    desc.regionMin = vec3(-3.0f, 0.0f, -3.0f);
    desc.regionMax = vec3(3.0f, 8.0f, 3.0f);
    desc.minSize = 0.1f;
    desc.maxSize = 0.2f;
    desc.boxFraction = 0.3f;
    desc.maxSpeed = 2.0f;
    desc.minRestitution = 0.1f;
    desc.maxRestitution = 0.8f;
    const PileResult cpu = RunPile(desc, kSeed, {.threads = 4});
    const PileResult gpu = RunPile(desc, kSeed, {.threads = 4, .gpuSolver = true});
    EXPECT_GE(cpu.colors, 4u);
    EXPECT_GT(cpu.contacts, 1500u);
    EXPECT_EQ(gpu.steps, 240u);
    ExpectSameBits(cpu, gpu);
}

// Spheres rolling with resistance on a dynamic slab: the slab touches more moving bodies than
// there are colours, so its manifolds spill into the overflow, which one GPU thread solves in
// order, and the rolling resistance rows do work.
TEST(GpuContactSolverTest, OverflowAndRollingGiveTheCpuSolversBits) {
    std::string why;
    if (!HaveGpuSolver(&why)) GTEST_SKIP() << why;
    SpawnDesc desc;
    desc.count = 600;
    desc.regionMin = vec3(-2.8f, 0.6f, -2.8f);
    desc.regionMax = vec3(2.8f, 2.0f, 2.8f);
    desc.minSize = 0.08f;
    desc.maxSize = 0.12f;
    desc.maxSpeed = 1.0f;
    const auto slabAndRolling = [](Registry& registry, std::vector<Entity>& bodies) {
        for (const Entity e : bodies) registry.Get<RigidBody>(e)->rollingResistance = 0.05f;
        const Entity slab = registry.Create();
        LocalTransform local;
        local.translation = vec3(0.0f, 0.25f, 0.0f);
        registry.Add(slab, local);
        RigidBody body;
        body.mass = 500.0f;
        registry.Add(slab, body);
        registry.Add(slab, Collider::Box(vec3(2.9f, 0.25f, 2.9f)));
        bodies.push_back(slab);
    };
    const PileResult cpu =
        RunPile(desc, kSeed, {.steps = 90, .threads = 3, .extras = slabAndRolling});
    const PileResult gpu = RunPile(
        desc, kSeed, {.steps = 90, .threads = 3, .gpuSolver = true, .extras = slabAndRolling});
    // 64 colours and the overflow.
    EXPECT_EQ(cpu.colors, ContactColoring::kColors + 1);
    ExpectSameBits(cpu, gpu);
}

// Without a device, the world says why and keeps solving on the CPU.
TEST(GpuContactSolverTest, WithoutADeviceTheWorldSaysWhy) {
    std::string why;
    if (HaveGpuSolver(&why)) GTEST_SKIP() << "this machine has a CUDA device";
    EXPECT_FALSE(why.empty());
    PhysicsWorld world;
    try {
        world.SolveContactsOnGpu();
        ADD_FAILURE() << "SolveContactsOnGpu did not throw";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot solve contacts on the GPU: " + why),
                  std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(world.SolvesContactsOnGpu());
}

}  // namespace
}  // namespace rtrt::physics
