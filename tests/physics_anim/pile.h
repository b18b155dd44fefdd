#pragma once
// What the physics suites share: planes, a walled pit, and a pile of random bodies rained into it
// and stepped, with every body's state at the end for bit-for-bit comparisons.
#include <tbb/task_arena.h>

#include <functional>
#include <vector>

#include "engine/physics_anim/physics_world.h"
#include "engine/physics_anim/random_spawn.h"

namespace rtrt::physics::test {

inline ecs::Entity AddPlane(ecs::Registry& registry, vec3 point, vec3 normal,
                            float restitution = 0.0f) {
    const ecs::Entity e = registry.Create();
    registry.Add(e, LocalTransform{point});
    RigidBody body;
    body.mass = 0.0f;
    body.restitution = restitution;
    registry.Add(e, body);
    registry.Add(e, Collider::Plane(normal));
    return e;
}

// Five planes: a floor at y = 0 and walls at x, z = +-halfWidth.
inline void AddPit(ecs::Registry& registry, float halfWidth) {
    AddPlane(registry, vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
    AddPlane(registry, vec3(-halfWidth, 0.0f, 0.0f), vec3(1.0f, 0.0f, 0.0f));
    AddPlane(registry, vec3(halfWidth, 0.0f, 0.0f), vec3(-1.0f, 0.0f, 0.0f));
    AddPlane(registry, vec3(0.0f, 0.0f, -halfWidth), vec3(0.0f, 0.0f, 1.0f));
    AddPlane(registry, vec3(0.0f, 0.0f, halfWidth), vec3(0.0f, 0.0f, -1.0f));
}

struct PileResult {
    std::vector<float> state;  // per body: position, orientation, velocity, angular velocity
    uint32_t colors = 0, contacts = 0;
    uint64_t steps = 0;
    uint32_t threads = 0;  // the steps could use (PhysicsStats::lastThreads)
};

struct PileRun {
    float halfWidth = 3.0f;  // of the pit
    int steps = 240;
    int threads = 1;
    // On every thread lent whatever the bodies (PhysicsSettings::minParallelBodies): the piles
    // here test the threaded step.
    uint32_t minParallelBodies = 0;
    bool gpuSolver = false;
    // Changes the spawned bodies (and may add some) before the first step.
    std::function<void(ecs::Registry&, std::vector<ecs::Entity>&)> extras;
};

// desc's bodies (from seed) rained into a walled pit and stepped as run says.
inline PileResult RunPile(const SpawnDesc& desc, uint64_t seed, const PileRun& run) {
    PileResult result;
    tbb::task_arena arena(run.threads);
    arena.execute([&] {
        ecs::Registry registry;
        AddPit(registry, run.halfWidth);
        std::vector<ecs::Entity> bodies = SpawnRandomBodies(registry, desc, seed);
        if (run.extras) run.extras(registry, bodies);
        PhysicsSettings settings;
        settings.minParallelBodies = run.minParallelBodies;
        PhysicsWorld world(settings);
        if (run.gpuSolver) world.SolveContactsOnGpu();
        world.Step(registry, run.steps);
        result.colors = world.Stats().lastColors;
        result.contacts = world.Stats().lastContacts;
        result.steps = world.Stats().steps;
        result.threads = world.Stats().lastThreads;
        for (const ecs::Entity e : bodies) {
            const RigidBody& b = *registry.Get<RigidBody>(e);
            const RigidBody::State& s = b.state;
            result.state.insert(
                result.state.end(),
                {s.position.x, s.position.y, s.position.z, s.orientation.x, s.orientation.y,
                 s.orientation.z, s.orientation.w, b.velocity.x, b.velocity.y, b.velocity.z,
                 b.angularVelocity.x, b.angularVelocity.y, b.angularVelocity.z});
        }
    });
    return result;
}

}  // namespace rtrt::physics::test
