#pragma once
// The runtime: a scene's entities in the ECS, moved by animation and physics on a fixed schedule,
// and extracted every frame into the instance records of a RenderScene. Only changed transforms
// are re-extracted, and what changed is handed on (Changes()) to the FrameRenderer, which owns
// the acceleration structures.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "engine/ecs/registry.h"
#include "engine/ecs/scheduler.h"
#include "engine/physics_anim/physics_world.h"
#include "engine/physics_anim/transform_system.h"
#include "engine/render_rt/render_scene.h"
#include "game/scene/loaded_scene.h"

namespace rtrt {

// Links an entity to its instance record in the RenderScene.
struct Renderable {
    uint32_t blasId = 0;
    uint32_t materialId = 0;
    uint32_t instance = UINT32_MAX;  // index in RenderScene::instances once extracted
};

// Links a deforming entity to its Deformation record in the RenderScene.
struct DeformationLink {
    uint32_t deformation = 0;
    float phase = 0.0f;  // procedural deformations: time offset of this instance
    double born = 0.0;   // world time the entity appeared
};

struct FrameStats {
    uint32_t spawned = 0;
    uint32_t extracted = 0;  // instance records rewritten this frame
    double simulateMs = 0.0, extractMs = 0.0;
};

class World {
  public:
    explicit World(const LoadedScene& scene);
    // The World keeps a reference to its scene, which a temporary would not outlive.
    explicit World(LoadedScene&&) = delete;

    // Advances time by dt: spawns what is due, runs the phases (physics, animation, transforms)
    // and extracts changed instances.
    FrameStats Advance(float dt);

    const RenderScene& Scene() const { return scene_; }
    // What the last Advance changed (after construction: every record, and the topology): what a
    // FrameRenderer's copy of the scene must receive.
    SceneChanges Changes() const { return {changed_, topologyChanged_, deformChanged_}; }
    double Time() const { return time_; }
    ecs::Registry& Registry() { return registry_; }
    const ecs::Registry& Registry() const { return registry_; }
    // Interactive edits (the window's spawn, drag and delete). They take effect at the next
    // Advance, which a paused frame loop calls with dt = 0.
    //
    // Adds a model or a material for later spawns; call before a FrameRenderer takes the scene.
    uint32_t AddBlas(std::shared_ptr<const Blas> blas);
    uint32_t AddMaterial(const Material& material);
    uint32_t AddPbrMaterial(const Material& approximation, const PbrMaterial& pbr);
    // Creates an entity as a scene file's spawner would (its spawnTime is ignored; a skin's
    // joints are not resolved: a spawned skinned mesh keeps its rest pose).
    ecs::Entity Spawn(const EntityDesc& desc);
    // Creates a group of entities (a glTF scene's nodes, InstantiateGltf's output) whose parent,
    // skin joint and morph animator indices point into the group itself; returns the first.
    ecs::Entity SpawnGroup(std::span<const EntityDesc> group);
    uint32_t AddDeformableMesh(std::shared_ptr<const DeformableMesh> mesh);
    uint32_t AddTexture(const Texture& texture, const uint32_t* rgba);
    // Moves an entity; a rigid body is teleported there and stops; an animated one keeps playing
    // its animation from there (PlaceAnimated).
    bool SetPose(ecs::Entity e, vec3 position, glm::quat rotation);
    // Destroys an entity and drops its instance: the last instance record moves into its slot.
    // Bodies asleep on it wake (WakeSleepersAround).
    bool Remove(ecs::Entity e);
    // Destroys the whole object e belongs to: the root of its hierarchy and everything under it
    // (a spawned glTF scene's nodes, skeleton and meshes), what the window's Delete means.
    bool RemoveObject(ecs::Entity e);
    // The root of the hierarchy e belongs to (e itself without a parent; null for a stale e): the
    // object the window picks, moves, turns and deletes.
    ecs::Entity ObjectRoot(ecs::Entity e) const;
    // The entity an instance record belongs to (a null entity for none).
    ecs::Entity EntityOfInstance(uint32_t instance) const;

    // The window's camera replaces the scene's (and its camera path) from now on.
    void OverrideCamera(const Camera& camera);
    // Any entity of the scene file has a rigid body: spawned objects are thrown, not placed.
    bool HasPhysics() const;

    // Per-system times of the last frame (physics, animators, transforms), for benchmarks.
    const ecs::Scheduler& Scheduler() const { return scheduler_; }
    // The rigid-body step's counts (bodies, contacts, colours) after the last frame.
    const physics::PhysicsStats& PhysicsStats() const { return physics_.Stats(); }
    // Solves the rigid bodies' contacts on the first CUDA device (the same values as on the CPU);
    // throws std::runtime_error saying why when there is none.
    void SolveContactsOnGpu() { physics_.SolveContactsOnGpu(); }
    // Every Advance is FRAME_DT long (an offline player): physics keeps up however long a frame
    // is, rather than running long frames in slow motion as a real-time loop must.
    void PlayAtFixedFrames(float frameDt) { physics_.KeepUpWithFrames(frameDt); }

  private:
    // Creates the entities whose time has come (time_); PENDINGDT is the step the systems are
    // still to advance them by (0 when nothing runs before the first image). Rigid bodies only
    // up to BODIESDUEBY, where the simulation is now: a body cannot be shifted in time.
    void SpawnDue(double pendingDt, double bodiesDueBy);
    ecs::Entity Create(const EntityDesc& desc);
    uint32_t Extract();
    // A Deformation for a new deforming entity: a released one of the same mesh and rest tree
    // if there is one (a despawned instance's), else a new record and BLAS slot.
    uint32_t AcquireDeformation(const EntityDesc& desc);
    void AdvanceDeformations();
    // Gives a deforming entity its Skin and MorphWeights. OFSCENE: D is one of the scene's
    // entities, whose joints and animator (LoadedScene::entities indices) are resolved; an
    // interactive spawn's are not (it keeps its rest pose and its given weights).
    // Skins and morph weights of a deforming entity; their entity indices point into `batch`
    // (the scene's entities, or a spawned group's).
    void AttachPose(const EntityDesc& d, ecs::Entity e, std::span<const ecs::Entity> batch);
    void ExtractPoses();

    const LoadedScene& source_;
    RenderScene scene_;
    ecs::Registry registry_;
    ecs::Scheduler scheduler_;
    physics::PhysicsWorld physics_;
    physics::TransformSystem transforms_;
    std::vector<uint32_t> changed_;
    std::vector<uint32_t> deformChanged_;     // deformation records rewritten this frame
    std::vector<uint32_t> deformPending_;     // ... by edits since the last Advance
    std::vector<uint32_t> freeDeformations_;  // released by removed entities
    std::optional<Camera> cameraOverride_;
    std::vector<ecs::Entity> instanceOwner_;  // instance record -> entity
    std::vector<ecs::Entity> created_;        // LoadedScene::entities index -> entity
    size_t nextSpawn_ = 0;
    bool topologyPending_ = true;  // entities created or destroyed since the last Advance
    bool topologyChanged_ = true;  // ... before the last Advance
    double time_ = 0.0;
};

}  // namespace rtrt
