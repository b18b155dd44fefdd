#pragma once
// The scene description that scene files and glTF files are loaded into, and what the runtime
// (World) plays: entities with their poses, animation and bodies, the camera path, the
// RenderScene at time 0.
#include <optional>
#include <string>
#include <vector>

#include "engine/physics_anim/animator.h"
#include "engine/physics_anim/collider.h"
#include "engine/physics_anim/rigid_body.h"
#include "engine/render_rt/output_transform.h"
#include "engine/render_rt/render_scene.h"

namespace rtrt {

// One entity a scene file asks for: an instance of a model, posed, maybe animated or simulated,
// appearing at spawnTime seconds (spawners and the timeline give later times).
struct EntityDesc {
    uint32_t blasId = 0;
    uint32_t materialId = 0;
    // A transform-only entity (a glTF node, the root of an included glTF scene) has no instance.
    bool renderable = true;
    // The entity whose transform this one's local pose is relative to: an index into
    // LoadedScene::entities, always smaller than this entity's (parents come first), or -1.
    int32_t parent = -1;
    // Where the entity came from, for messages: sourceArray[sourceIndex] ("instances", 3).
    const char* sourceArray = "instances";
    uint32_t sourceIndex = 0;
    physics::LocalTransform local;
    std::optional<physics::Animator> animator;
    std::optional<physics::RigidBody> body;  // with collider, derived from the model's shape
    physics::Collider collider;
    float spawnTime = 0.0f;
    // A deforming instance: the RenderScene::deformableMeshes index of its mesh, whose rest tree
    // is blasId (-1: the instance shows blasId as it is). Each such entity gets a Deformation
    // of its own, so instances of one mesh deform independently.
    int32_t deformableMesh = -1;
    // Its procedural deformation; `time` is its phase, added to the time since it appeared.
    ProceduralDeform procedural;
    // A skinned deforming instance: its joints, other entities of the scene (World makes them
    // the physics::Skin's joints), one per joint of the mesh's skin.
    struct SkinDesc {
        std::vector<int32_t> joints;         // LoadedScene::entities indices, of its spawn time
        std::vector<glm::mat4> inverseBind;  // one per joint
    };
    std::optional<SkinDesc> skin;
    // A morphing deforming instance: its weights at the start, one per morph target, and the
    // entity whose animator's clip (its weights track) plays them (a LoadedScene::entities
    // index, -1: none; they then stay as given).
    struct MorphDesc {
        std::vector<float> weights;
        int32_t animator = -1;
    };
    std::optional<MorphDesc> morph;
};

// A camera key of the scene's camera_path; the camera moves linearly between keys.
struct CameraKey {
    float time = 0.0f;
    vec3 position{0.0f};
    vec3 lookAt{0.0f};
};

// What a glTF file brought into a scene (rtrt info prints it).
struct GltfSummary {
    std::string file;
    uint32_t nodes = 0, meshes = 0, primitives = 0, vertices = 0, triangles = 0;
    uint32_t materials = 0, textures = 0, cameras = 0, lights = 0, animations = 0;
    uint32_t animatedNodes = 0;
    uint32_t skins = 0, deformingPrimitives = 0;  // skinned or morphed primitives, as read
    float animationSeconds = 0.0f;                // of the animation played (the first)
};

// Every entity a scene asks for (instances, spawned bodies, the nodes of each glTF placement, a
// glTF file shown alone) counts against one budget, so that no combination of spawners and glTF
// node trees asks for more memory than a machine has.
inline constexpr uint64_t kMaxSceneEntities = 2000000;

struct LoadedScene {
    // The scene at time 0: every entity with spawnTime 0 in its initial pose, TLAS built.
    RenderScene scene;
    std::optional<uint32_t> width, height;   // the file's "image" size, if it gives one
    std::vector<EntityDesc> entities;        // everything the file places or spawns, by time
    std::vector<CameraKey> cameraPath;       // empty: the camera stays where "camera" puts it
    bool dynamic = false;                    // any animator, rigid body, later spawn or camera path
    std::vector<std::string> modelNames;     // by BLAS id
    std::vector<std::string> materialNames;  // by material id (a grey default, if used, comes last)
    std::vector<GltfSummary> gltfFiles;      // the glTF files loaded or included
    // From linear radiance to the image: the scene's colour convention, exposure and tone map.
    OutputTransform output = kDisplayValues;
};

// The camera of a scene at time t (its camera_path if it has one).
Camera CameraAt(const LoadedScene& scene, double t);

// The last step of loading: entities ordered by spawn time (parents stay ahead of their
// children), an instance for every renderable entity of time 0 at its world pose, the TLAS.
// Throws InputError(file, e.g. "instances[3]", ...) when an entity's world bounds are not finite
// (positions and scales each in range can still multiply beyond float range).
void FinishLoadedScene(LoadedScene& out, const std::string& file);

// The world matrix of every entity in its initial pose (parent chains followed).
std::vector<glm::mat4> InitialWorlds(const LoadedScene& out);

}  // namespace rtrt
