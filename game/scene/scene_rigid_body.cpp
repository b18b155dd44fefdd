#include "game/scene/scene_rigid_body.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <vector>

#include "engine/core/error.h"
#include "engine/physics_anim/broad_phase.h"

namespace rtrt {
namespace {

// What the rigid-body simulation handles, in metres, kilograms and seconds: beyond these its
// floats overflow (inverse masses and inertias, squared speeds) or are too coarse to resolve
// contacts.
constexpr float kMaxBodyCoordinate = 1e5f;  // 100 km from the origin
constexpr float kMinBodyMass = 1e-6f;
constexpr float kMinColliderSize = 1e-4f;  // a sphere's radius, a box's half side
constexpr float kMaxColliderSize = 1e5f;
constexpr float kMaxBodySpeed = 1e6f;  // per component; the world clamps speeds far below

bool WithinWorld(vec3 p) { return MaxComponent(glm::abs(p)) <= kMaxBodyCoordinate; }

}  // namespace

void ParseRigidBody(const Json& j, const std::string& path, const std::string& file,
                    const ModelShape& shape, const std::string& modelName, EntityDesc& e) {
    JsonFields f(j, path, file);
    physics::RigidBody body;
    body.mass = f.InRange("mass", 0.0f, 1e9f, body.mass);
    // As written: 1e-50 is 0 as a float, which would make the body static.
    const bool someMass = f.Has("mass") && f.Get("mass").get<double>() > 0.0;
    if (someMass && body.mass < kMinBodyMass)
        f.Fail("mass", "a moving body weighs at least 1e-6 kg (0 makes it static)");
    if (f.Has("static")) {
        f.ExpectKind("static", JsonKind::kBool);
        const bool isStatic = f.Get("static").get<bool>();
        if (isStatic && f.Has("mass"))
            f.Fail("mass", "a static body has no mass: leave mass out, or static");
        if (!isStatic && shape.kind == ModelShape::kPlane)
            f.Fail("static", "a plane is always static: leave static out");
        if (!isStatic && f.Has("mass") && body.mass == 0.0f)
            f.Fail("static", "a body of mass 0 is static: give it a mass, or leave static out");
        if (isStatic) body.mass = 0.0f;
    }
    body.restitution = f.InRange("restitution", 0.0f, 1.0f, body.restitution);
    body.friction = f.InRange("friction", 0.0f, 10.0f, body.friction);
    body.velocity = f.Vec3("velocity", vec3(0.0f));
    if (MaxComponent(glm::abs(body.velocity)) > kMaxBodySpeed)
        f.Fail("velocity", "each component must be within 1e6 m/s");
    // What a static body or a plane would ignore is refused rather than dropped silently.
    const bool plane = shape.kind == ModelShape::kPlane;
    if (plane && f.Has("mass") && body.mass > 0.0f)
        f.Fail("mass", "a plane is always static: leave mass out");
    if (plane && body.velocity != vec3(0.0f))
        f.Fail("velocity", "a plane is always static: leave velocity out");
    if (body.mass == 0.0f && body.velocity != vec3(0.0f))
        f.Fail("velocity", "a static body does not move: leave velocity out, or give it a mass");
    f.Finish();
    if (!WithinWorld(e.local.translation))
        throw InputError(file, path,
                         "a rigid body must start within 100 km (1e5) of the origin on each "
                         "axis: floats are too coarse beyond");
    const vec3 scale = e.local.scale;
    const auto checkSize = [&](vec3 size, const char* what) {
        if (std::min({size.x, size.y, size.z}) >= kMinColliderSize &&
            MaxComponent(size) <= kMaxColliderSize)
            return;
        throw InputError(file, path,
                         std::string("a rigid body's ") + what +
                             " (the model's times the scale) must be within 1e-4 to 1e5 m");
    };
    switch (shape.kind) {
        case ModelShape::kSphere:
            // The collider is a sphere: an ellipsoid's would rest on its longest axis.
            if (MaxComponent(scale) - std::min({scale.x, scale.y, scale.z}) >
                1e-6f * MaxComponent(scale))
                throw InputError(file, path,
                                 "a sphere rigid body needs a uniform scale (one number or three "
                                 "equal ones): its collider is a sphere");
            e.collider = physics::Collider::Sphere(shape.radius * MaxComponent(scale));
            checkSize(vec3(e.collider.radius), "sphere radius");
            break;
        case ModelShape::kBox:
            e.collider = physics::Collider::Box(shape.halfExtents * scale);
            checkSize(e.collider.halfExtents, "box half sides");
            break;
        case ModelShape::kPlane:
            // In the body's frame, as every collider: the world turns it by the body's rotation
            // (turned here as well, a plane at 90 degrees collided as one at 180).
            e.collider = physics::Collider::Plane(vec3(0, 1, 0));
            body.mass = 0.0f;  // planes do not move
            break;
        default:
            throw InputError(
                file, path,
                "a rigid body needs a sphere, box or plane model; \"" + modelName + "\" is a mesh");
    }
    e.body = body;
}

void CheckRigidBodyPlaces(const JsonFields& f, const std::string& field,
                          std::span<const vec3> places) {
    for (const vec3& p : places) {
        if (!WithinWorld(p))
            f.Fail(field, "a rigid body would start beyond 100 km (1e5) of the origin");
    }
}

// The instance or spawner to give room first among BODIES (BOXES, one each) that overlap in too
// many pairs: one whose bodies alone do, else the one that brings the most moving bodies (static
// ones never pair with each other).
static std::string PackedSource(const std::vector<const EntityDesc*>& bodies,
                                const std::vector<physics::BroadPhaseBox>& boxes) {
    std::map<std::pair<std::string, uint32_t>, std::vector<physics::BroadPhaseBox>> bySource;
    std::map<std::pair<std::string, uint32_t>, size_t> moving;
    for (size_t i = 0; i < bodies.size(); ++i) {
        const std::pair<std::string, uint32_t> source{bodies[i]->sourceArray,
                                                      bodies[i]->sourceIndex};
        bySource[source].push_back(boxes[i]);
        moving[source] += boxes[i].isStatic ? 0 : 1;
    }
    auto name = [](const std::pair<std::string, uint32_t>& s) {
        return s.first + "[" + std::to_string(s.second) + "]";
    };
    for (const auto& [source, own] : bySource) {
        physics::SweepAndPrune sweep;
        sweep.SetPairLimit(32 * own.size() + 100000);
        std::vector<std::pair<uint32_t, uint32_t>> pairs;
        if (!sweep.FindPairs(own, pairs)) return name(source);
    }
    return name(std::max_element(moving.begin(), moving.end(), [](const auto& a, const auto& b) {
                    return a.second < b.second;
                })->first);
}

void CheckRigidBodiesHaveRoom(const LoadedScene& scene, const std::string& file) {
    // The bodies that may appear together. A frame spawns every body whose time has come, and a
    // frame of play is at most 1 s of scene time (its --fps is at least 1), so bodies of times
    // less than 1 s apart may start in one frame: each whole second (ceil(t)) is checked with
    // the next, which covers every such pair (and some up to 2 s apart), the ones of time 0
    // (the static scenery) first.
    std::map<int64_t, std::vector<physics::BroadPhaseBox>> bySecond;
    std::map<int64_t, std::vector<const EntityDesc*>> sources;  // each box's entity
    for (const EntityDesc& e : scene.entities) {
        if (!e.body || e.collider.shape == physics::ColliderShape::kPlane) continue;
        const vec3 half = physics::WorldHalfExtent(e.collider, glm::mat3_cast(e.local.rotation));
        const int64_t second = int64_t(std::ceil(double(e.spawnTime)));
        bySecond[second].push_back(
            {e.local.translation - half, e.local.translation + half, e.body->mass == 0});
        sources[second].push_back(&e);
    }
    for (auto second = bySecond.begin(); second != bySecond.end(); ++second) {
        std::vector<physics::BroadPhaseBox> boxes = second->second;
        std::vector<const EntityDesc*> from = sources[second->first];
        if (const auto next = std::next(second);
            next != bySecond.end() && next->first == second->first + 1) {
            boxes.insert(boxes.end(), next->second.begin(), next->second.end());
            from.insert(from.end(), sources[next->first].begin(), sources[next->first].end());
        }
        // A few touching neighbours each, as in any pile, and room to spare; bodies packed into
        // one place touch every other (1,000 balls in one spot took 830 MB a step, 4,000 more
        // than 8 GB), and the simulation holds every touching pair.
        const size_t limit = 32 * boxes.size() + 100000;
        physics::SweepAndPrune sweep;
        sweep.SetPairLimit(limit);
        std::vector<std::pair<uint32_t, uint32_t>> pairs;
        if (sweep.FindPairs(boxes, pairs)) continue;
        const int64_t start = std::max<int64_t>(second->first - 1, 0);
        throw InputError(file, PackedSource(from, boxes) + ".rigid_body",
                         std::to_string(boxes.size()) + " rigid bodies that start between " +
                             std::to_string(start) + " and " + std::to_string(second->first + 1) +
                             " s (so maybe in one frame) overlap in more than " +
                             std::to_string(limit) +
                             " pairs (packed into one place), each of which the simulation "
                             "would hold: give them room (a grid spacing above their size, or a "
                             "rain)");
    }
}

}  // namespace rtrt
