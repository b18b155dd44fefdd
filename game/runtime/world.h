#pragma once
// The runtime: a scene's entities in the ECS, moved by animation and physics on a fixed schedule,
// and extracted every frame into the RenderScene the back ends trace. Only changed transforms are
// re-extracted; the TLAS is an LBVH refit or rebuilt by the DynamicTlas policy.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "engine/bvh/tlas/dynamic_tlas.h"
#include "engine/ecs/registry.h"
#include "engine/ecs/scheduler.h"
#include "engine/physics_anim/physics_world.h"
#include "engine/physics_anim/transform_system.h"
#include "game/scene/loaded_scene.h"

namespace rtrt {

// Links an entity to its instance record in the RenderScene.
struct Renderable {
    uint32_t blasId = 0;
    uint32_t materialId = 0;
    uint32_t instance = UINT32_MAX;  // index in RenderScene::instances once extracted
};

struct FrameStats {
    uint32_t spawned = 0;
    uint32_t extracted = 0;  // instance records rewritten this frame
    bool tlasRebuilt = false;
    double simulateMs = 0.0, extractMs = 0.0, tlasMs = 0.0;
};

class World {
  public:
    // hostTlas: keep the CPU's TLAS up to date (the CPU back end traces it). A GPU frame loop
    // builds its own on the device (CudaFrameRenderer) and passes false.
    explicit World(const LoadedScene& scene, TlasPolicy policy = {false, 0.25f},
                   bool hostTlas = true);

    // Advances time by dt: spawns what is due, runs the phases (physics, animation, transforms),
    // extracts changed instances and brings the TLAS up to date.
    FrameStats Advance(float dt);

    const RenderScene& Scene() const { return scene_; }
    // The instance records rewritten or added by the last Advance (all of them after
    // construction): what a GPU copy of the scene must receive.
    const std::vector<uint32_t>& ChangedInstances() const { return changed_; }
    double Time() const { return time_; }
    ecs::Registry& Registry() { return registry_; }
    // Interactive edits (the window's spawn, drag and delete). They take effect at the next
    // Advance, which a paused frame loop calls with dt = 0.
    //
    // Adds a model or a material for later spawns; call before a GPU renderer uploads the scene.
    uint32_t AddBlas(std::shared_ptr<const Blas> blas);
    uint32_t AddMaterial(const Material& material);
    // Creates an entity as a scene file's spawner would (its spawnTime is ignored).
    ecs::Entity Spawn(const EntityDesc& desc);
    // Moves an entity; a rigid body is teleported there and stops.
    bool SetPose(ecs::Entity e, vec3 position, glm::quat rotation);
    // Destroys an entity and drops its instance: the last instance record moves into its slot.
    bool Remove(ecs::Entity e);
    // The entity an instance record belongs to (a null entity for none).
    ecs::Entity EntityOfInstance(uint32_t instance) const;

    // The window's camera replaces the scene's (and its camera path) from now on.
    void OverrideCamera(const Camera& camera);
    // Whether the host keeps a TLAS (the CPU back end traces it); turning it on builds one now.
    void SetHostTlas(bool on);
    // Any entity of the scene file has a rigid body: spawned objects are thrown, not placed.
    bool HasPhysics() const;

    // Per-system times of the last frame (physics, animators, transforms), for benchmarks.
    const ecs::Scheduler& Scheduler() const { return scheduler_; }

  private:
    void SpawnDue();
    ecs::Entity Create(const EntityDesc& desc);
    uint32_t Extract();
    // Refits or rebuilds the TLAS (per the policy) and hands it to the RenderScene.
    bool UpdateTlas();

    const LoadedScene& source_;
    RenderScene scene_;
    ecs::Registry registry_;
    ecs::Scheduler scheduler_;
    physics::PhysicsWorld physics_;
    physics::TransformSystem transforms_;
    DynamicTlas tlas_;
    std::vector<Aabb> blasBounds_;
    std::vector<uint32_t> changed_;
    std::optional<Camera> cameraOverride_;
    std::vector<ecs::Entity> instanceOwner_;  // instance record -> entity
    std::vector<ecs::Entity> created_;        // LoadedScene::entities index -> entity
    bool hostTlas_ = true;
    size_t nextSpawn_ = 0;
    bool topologyChanged_ = true;
    double time_ = 0.0;
};

}  // namespace rtrt
