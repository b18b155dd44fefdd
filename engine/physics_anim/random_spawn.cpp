#include "engine/physics_anim/random_spawn.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "engine/physics_anim/collider.h"
#include "engine/physics_anim/rigid_body.h"
#include "engine/physics_anim/transform.h"

namespace rtrt::physics {

namespace {

class Random {
  public:
    explicit Random(uint64_t seed) : engine_(seed) {}
    // Uniform in [0, 1): the top 24 bits, exactly representable in a float.
    float Unit() { return static_cast<float>(engine_() >> 40) * 0x1p-24f; }
    float Range(float lo, float hi) { return lo + (hi - lo) * Unit(); }

  private:
    std::mt19937_64 engine_;
};

// Shoemake 1992, "Uniform Random Rotations" (Graphics Gems III).
glm::quat RandomRotation(Random& random) {
    const float u1 = random.Unit();
    const float a = 2.0f * kPi * random.Unit();
    const float b = 2.0f * kPi * random.Unit();
    const float s1 = std::sqrt(1.0f - u1);
    const float s2 = std::sqrt(u1);
    return glm::normalize(
        glm::quat(s2 * std::cos(b), s1 * std::sin(a), s1 * std::cos(a), s2 * std::sin(b)));
}

}  // namespace

std::vector<ecs::Entity> SpawnRandomBodies(ecs::Registry& registry, const SpawnDesc& desc,
                                           uint64_t seed) {
    Random random(seed);
    const float maxSize = std::max(desc.minSize, desc.maxSize);
    // A box's corner reaches sqrt(3) half extents from its centre.
    const float reach = desc.boxFraction > 0.0f ? maxSize * std::sqrt(3.0f) : maxSize;
    const float cell = 2.0f * reach * 1.02f;
    const vec3 extent = desc.regionMax - desc.regionMin;
    const auto nx = static_cast<uint32_t>(std::max(0.0f, std::floor(extent.x / cell)));
    const auto ny = static_cast<uint32_t>(std::max(0.0f, std::floor(extent.y / cell)));
    const auto nz = static_cast<uint32_t>(std::max(0.0f, std::floor(extent.z / cell)));
    const uint64_t cells = static_cast<uint64_t>(nx) * ny * nz;
    const auto count = static_cast<uint32_t>(std::min<uint64_t>(desc.count, cells));

    std::vector<ecs::Entity> spawned;
    spawned.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t ix = i % nx;
        const uint32_t iz = (i / nx) % nz;
        const uint32_t iy = i / (nx * nz);
        const bool isBox = random.Unit() < desc.boxFraction;
        Collider collider;
        float bodyReach;
        float volume;
        if (isBox) {
            const vec3 h(random.Range(desc.minSize, maxSize), random.Range(desc.minSize, maxSize),
                         random.Range(desc.minSize, maxSize));
            collider = Collider::Box(h);
            bodyReach = glm::length(h);
            volume = 8.0f * h.x * h.y * h.z;
        } else {
            const float r = random.Range(desc.minSize, maxSize);
            collider = Collider::Sphere(r);
            bodyReach = r;
            volume = 4.0f / 3.0f * kPi * r * r * r;
        }
        // Jitter within the room the body leaves in its cell.
        const float slack = std::max(0.0f, 0.5f * cell - bodyReach);
        const vec3 centre = desc.regionMin + cell * (vec3(ix, iy, iz) + 0.5f);
        LocalTransform local;
        local.translation = centre + vec3(random.Range(-slack, slack), random.Range(-slack, slack),
                                          random.Range(-slack, slack));
        if (desc.randomOrientation) local.rotation = RandomRotation(random);
        RigidBody body;
        body.mass = desc.density * volume;
        body.velocity = vec3(random.Range(-desc.maxSpeed, desc.maxSpeed),
                             random.Range(-desc.maxSpeed, desc.maxSpeed),
                             random.Range(-desc.maxSpeed, desc.maxSpeed));
        body.restitution = random.Range(desc.minRestitution, desc.maxRestitution);
        body.friction = desc.friction;

        const ecs::Entity e = registry.Create();
        registry.Add(e, local);
        registry.Add(e, body);
        registry.Add(e, collider);
        spawned.push_back(e);
    }
    return spawned;
}

}  // namespace rtrt::physics
