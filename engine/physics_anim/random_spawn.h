#pragma once
// Seeded random placement of rigid bodies, for demos, benchmarks and tests.
#include <cstdint>
#include <vector>

#include "engine/core/math.h"
#include "engine/ecs/registry.h"

namespace rtrt::physics {

struct SpawnDesc {
    uint32_t count = 100;
    vec3 regionMin{-5.0f, 1.0f, -5.0f};
    vec3 regionMax{5.0f, 10.0f, 5.0f};
    float minSize = 0.1f;  // sphere radius or box half extent (each axis drawn separately)
    float maxSize = 0.3f;
    float boxFraction = 0.0f;  // probability that a body is a box rather than a sphere
    float maxSpeed = 0.0f;     // initial velocity: each component uniform in [-maxSpeed, maxSpeed]
    float minRestitution = 0.3f;
    float maxRestitution = 0.3f;
    float friction = 0.5f;
    float density = 1000.0f;  // kg/m^3: mass follows the volume
    bool randomOrientation = true;
};

// Creates up to desc.count bodies (LocalTransform, RigidBody, Collider) on a jittered lattice
// filling the region from its low corner, x fastest, then z, then y, so that no two overlap:
// the lattice cell holds the largest body in any orientation. Fewer are made when the region
// holds fewer cells. The same seed gives the same bodies on every platform: the generator is
// std::mt19937_64, whose sequence the standard fixes, turned into floats by our own arithmetic
// (the standard distributions differ between libraries).
std::vector<ecs::Entity> SpawnRandomBodies(ecs::Registry& registry, const SpawnDesc& desc,
                                           uint64_t seed);

}  // namespace rtrt::physics
