#include "game/world.h"

#include <glm/gtc/matrix_inverse.hpp>

#include "engine/core/timer.h"
#include "engine/physics_anim/physics_anim_systems.h"

namespace rtrt {

World::World(const LoadedScene& scene, TlasPolicy policy, bool hostTlas)
    : source_(scene), tlas_(policy), hostTlas_(hostTlas) {
    scene_.blases = scene.scene.blases;
    scene_.materials = scene.scene.materials;
    scene_.lights = scene.scene.lights;
    scene_.camera = scene.scene.camera;
    scene_.background = scene.scene.background;
    scene_.maxDepth = scene.scene.maxDepth;
    for (const auto& blas : scene_.blases) blasBounds_.push_back(blas->bounds);
    physics::AddPhysicsAnimSystems(scheduler_, physics_, transforms_);
    SpawnDue();
    transforms_.Update(registry_);
    Extract();
    UpdateTlas();
}

bool World::UpdateTlas() {
    if (!hostTlas_) {
        topologyChanged_ = false;
        return false;
    }
    const bool rebuilt = tlas_.Update(scene_.instances, blasBounds_, topologyChanged_).rebuilt;
    scene_.SetTlas({tlas_.Tree().nodes, tlas_.Tree().primOrder});
    topologyChanged_ = false;
    return rebuilt;
}

void World::SpawnDue() {
    const std::vector<EntityDesc>& entities = source_.entities;
    for (; nextSpawn_ < entities.size() && entities[nextSpawn_].spawnTime <= time_; ++nextSpawn_) {
        const EntityDesc& d = entities[nextSpawn_];
        const ecs::Entity e = registry_.Create();
        registry_.Add(e, d.local);
        registry_.Add(e, Renderable{d.blasId, d.materialId});
        if (d.animator) registry_.Add(e, *d.animator);
        if (d.body) {
            registry_.Add(e, *d.body);
            registry_.Add(e, d.collider);
        }
        topologyChanged_ = true;
    }
}

// Rewrites the instance records of the entities whose world transform changed.
uint32_t World::Extract() {
    uint32_t extracted = 0;
    registry_.EachChanged<physics::WorldTransform>([&](ecs::Entity e, physics::WorldTransform& w) {
        Renderable* r = registry_.Get<Renderable>(e);
        if (!r) return;
        if (r->instance == UINT32_MAX) {
            r->instance = scene_.AddInstance(r->blasId, r->materialId, w.objectToWorld);
            changed_.push_back(r->instance);
        } else {
            Instance& inst = scene_.instances[r->instance];
            inst.objectToWorld = AffineFromMat4(w.objectToWorld);
            inst.worldToObject = AffineFromMat4(glm::affineInverse(w.objectToWorld));
            changed_.push_back(r->instance);
        }
        ++extracted;
    });
    registry_.ClearChanged<physics::WorldTransform>();
    return extracted;
}

FrameStats World::Advance(float dt) {
    FrameStats stats;
    changed_.clear();
    time_ += dt;
    const size_t before = nextSpawn_;
    SpawnDue();
    stats.spawned = uint32_t(nextSpawn_ - before);
    Stopwatch timer;
    scheduler_.RunFrame(registry_, dt);
    stats.simulateMs = timer.Milliseconds();
    timer.Restart();
    stats.extracted = Extract();
    stats.extractMs = timer.Milliseconds();
    timer.Restart();
    if (stats.extracted > 0 || topologyChanged_) stats.tlasRebuilt = UpdateTlas();
    stats.tlasMs = timer.Milliseconds();
    scene_.camera = CameraAt(source_, float(time_));
    return stats;
}

}  // namespace rtrt
