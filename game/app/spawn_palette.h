#pragma once
// What the window can spawn in front of the camera: a sphere, the teapot, the dragon (res4), a
// glass sphere, a mirror box and the walking character (assets/models/walker.gltf, skinned and
// animated: each spawned copy walks in a phase of its own). Their models and materials are added to
// the World once, before a GPU renderer uploads the scene; models whose files are missing are left
// out with a note.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/bvh/traversal/two_level_traversal.h"
#include "engine/core/ray.h"
#include "game/gltf/gltf_asset.h"
#include "game/runtime/world.h"

namespace rtrt {

struct SpawnKind {
    std::string name;
    uint32_t blasId = 0, materialId = 0;
    physics::Collider collider;  // used when the scene has physics
    float scale = 1.0f;
    std::shared_ptr<const GltfAsset> gltf;  // a glTF scene spawned whole (its nodes, skins)
};

// Finds the nearest hit of a ray in the scene as the frame renderer sees it (FrameRenderer::Pick).
using ScenePick = std::function<bool(const Ray& ray, SceneHit* hit)>;

// Where a character spawned now stands: on what lies below the point where the view's centre
// meets the scene (half a unit back toward the camera, so a wall hit leaves it in front of the
// wall), or below the point DISTANCE ahead when the view meets nothing; at least 2 units ahead
// of the camera across the ground, so that a low camera looking down does not stand it in the
// camera. Things that move (dynamic bodies, characters, animated objects) are looked through: a
// character stood on a falling ball was left in the air. Empty when nothing lies below.
std::optional<vec3> SpawnGround(const World& world, const Camera& camera, float distance,
                                const ScenePick& pick);

class SpawnPalette {
  public:
    // Adds the models and materials to the world; `notes` receives what was left out and why.
    SpawnPalette(World& world, std::vector<std::string>* notes);

    const std::vector<SpawnKind>& Kinds() const { return kinds_; }
    const SpawnKind* Find(const std::string& name) const;
    // Spawns `kind` `distance` ahead of the camera; with physics it is thrown along the view. A
    // glTF kind (a character) stands at `ground` when given (where the view meets the scene:
    // the window finds it), else on y = 0 under the point ahead.
    ecs::Entity SpawnInFront(World& world, const SpawnKind& kind, const Camera& camera,
                             float distance, const vec3* ground = nullptr) const;

    static constexpr float kThrowSpeed = 6.0f;  // m/s

  private:
    void AddGltf(World& world, const std::string& name, const std::string& path,
                 std::vector<std::string>* notes);

    std::vector<SpawnKind> kinds_;
    mutable uint32_t spawnedGltf_ = 0;  // spreads the phases of spawned glTF copies
};

}  // namespace rtrt
