#include "game/scene/scene_rigid_body.h"

#include <algorithm>
#include <glm/glm.hpp>

#include "engine/core/error.h"

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
    if (body.mass > 0.0f && body.mass < kMinBodyMass)
        f.Fail("mass", "a moving body weighs at least 1e-6 kg (0 makes it static)");
    if (f.Has("static") && f.Get("static").is_boolean() && f.Get("static").get<bool>())
        body.mass = 0.0f;
    body.restitution = f.InRange("restitution", 0.0f, 1.0f, body.restitution);
    body.friction = f.InRange("friction", 0.0f, 10.0f, body.friction);
    body.velocity = f.Vec3("velocity", vec3(0.0f));
    if (MaxComponent(glm::abs(body.velocity)) > kMaxBodySpeed)
        f.Fail("velocity", "each component must be within 1e6 m/s");
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
            e.collider = physics::Collider::Sphere(shape.radius * MaxComponent(scale));
            checkSize(vec3(e.collider.radius), "sphere radius");
            break;
        case ModelShape::kBox:
            e.collider = physics::Collider::Box(shape.halfExtents * scale);
            checkSize(e.collider.halfExtents, "box half sides");
            break;
        case ModelShape::kPlane:
            e.collider = physics::Collider::Plane(e.local.rotation * vec3(0, 1, 0));
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

}  // namespace rtrt
