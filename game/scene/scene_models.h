#pragma once
// The models of a scene file ("models": {"name": {"type": ...}}) other than glTF scenes, which
// gltf_import.h reads.
#include <string>

#include "engine/bvh/blas/blas.h"
#include "game/scene/json_fields.h"

namespace rtrt {

// What a model tells a rigid body about its collider: a sphere's radius, a box's half size, or
// that it is a plane; kOther (meshes, teapots, sphere sets) cannot be simulated.
struct ModelShape {
    enum Kind { kOther, kSphere, kBox, kPlane } kind = kOther;
    float radius = 0.0f;
    vec3 halfExtents{0.0f};
};

// Builds the BLAS of the model F describes (sphere, spheres, box, plane, teapot or mesh) and sets
// SHAPE for the types that have one; BASEDIR resolves file paths. Throws InputError naming the
// field for anything malformed.
Blas ParseSceneModel(JsonFields& f, const std::string& baseDir, ModelShape& shape);

}  // namespace rtrt
