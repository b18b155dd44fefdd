#pragma once
// rtrt scene files (JSON; the format is documented in the README).
#include <optional>
#include <string>
#include <vector>

#include "engine/physics_anim/animator.h"
#include "engine/physics_anim/collider.h"
#include "engine/physics_anim/rigid_body.h"
#include "engine/render_rt/render_scene.h"

namespace rtrt {

// One entity a scene file asks for: an instance of a model, posed, maybe animated or simulated,
// appearing at spawnTime seconds (spawners and the timeline give later times).
struct EntityDesc {
    uint32_t blasId = 0;
    uint32_t materialId = 0;
    physics::LocalTransform local;
    std::optional<physics::Animator> animator;
    std::optional<physics::RigidBody> body;  // with collider, derived from the model's shape
    physics::Collider collider;
    float spawnTime = 0.0f;
};

// A camera key of the scene's camera_path; the camera moves linearly between keys.
struct CameraKey {
    float time = 0.0f;
    vec3 position{0.0f};
    vec3 lookAt{0.0f};
};

struct LoadedScene {
    // The scene at time 0: every entity with spawnTime 0 in its initial pose, TLAS built.
    RenderScene scene;
    std::optional<uint32_t> width, height;   // the file's "image" size, if it gives one
    std::vector<EntityDesc> entities;        // everything the file places or spawns, by time
    std::vector<CameraKey> cameraPath;       // empty: the camera stays where "camera" puts it
    bool dynamic = false;                    // any animator, rigid body, later spawn or camera path
    std::vector<std::string> modelNames;     // by BLAS id
    std::vector<std::string> materialNames;  // by material id (a grey default, if used, comes last)
};

// The camera of a scene at time t (its camera_path if it has one).
Camera CameraAt(const LoadedScene& scene, float t);

// Reads a scene file and builds its BLASes and TLAS. Throws InputError naming the file, the
// field (e.g. "instances[2].scale") and the reason for anything malformed.
LoadedScene LoadSceneFile(const std::string& path);

// Same, from JSON text; `name` stands for the file in messages and `baseDir` resolves paths.
LoadedScene ParseScene(const std::string& text, const std::string& name,
                       const std::string& baseDir);

}  // namespace rtrt
