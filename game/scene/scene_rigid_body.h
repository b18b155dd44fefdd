#pragma once
// A scene entity's "rigid_body": its body and collider, within what the simulation handles.
#include <span>
#include <string>

#include "game/scene/json_fields.h"
#include "game/scene/loaded_scene.h"
#include "game/scene/scene_models.h"

namespace rtrt {

// Sets e.body and e.collider from j (at path in file) and the model's shape. The collider
// follows the model: a sphere (radius x largest scale), a box (half size x scale) or a plane
// (its normal turned by the rotation); modelName names a model that cannot be simulated.
void ParseRigidBody(const Json& j, const std::string& path, const std::string& file,
                    const ModelShape& shape, const std::string& modelName, EntityDesc& e);

// Fails on field of f when a spawner would start a rigid body at one of places that lies beyond
// the simulated world.
void CheckRigidBodyPlaces(const JsonFields& f, const std::string& field,
                          std::span<const vec3> places);

// Fails when the scene's rigid bodies (all its instances' and spawners', each where it starts)
// are packed so closely that the simulation's pairs of nearby bodies would grow with the square
// of their number.
void CheckRigidBodiesHaveRoom(const LoadedScene& scene, const std::string& file);

}  // namespace rtrt
