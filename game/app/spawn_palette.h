#pragma once
// What the window can spawn in front of the camera: a sphere, the teapot, the dragon (res4), a
// glass sphere, a mirror box and the walking character (assets/models/walker.gltf, skinned and
// animated: each spawned copy walks in a phase of its own). Their models and materials are added to
// the World once, before a GPU renderer uploads the scene; models whose files are missing are left
// out with a note.
#include <string>
#include <vector>

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
