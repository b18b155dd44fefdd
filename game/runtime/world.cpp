#include "game/runtime/world.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "engine/core/timer.h"
#include "engine/physics_anim/animator.h"
#include "engine/physics_anim/physics_anim_systems.h"
#include "engine/physics_anim/skinning.h"
#include "engine/physics_anim/transform_system.h"
#include "engine/physics_anim/wake_around.h"

namespace rtrt {

namespace {

// A procedural deformation's clock at T seconds, reduced in double to one period of its motion
// (a wave's wavelength / speed, a twist's 2 pi / speed): the deformers evaluate it in float, in
// which a clock past 1e5 s moves only every few frames and a wave's argument loses its shape.
float DeformClock(const ProceduralDeform& p, double t) {
    constexpr double kTwoPi = 6.283185307179586;
    const double speed = std::fabs(double(p.speed));
    const double period =
        p.kind == ProceduralDeformKind::kWave ? double(p.wavelength) / speed : kTwoPi / speed;
    // A clock within one period needs no reduction (a still deformation's period is infinite; a
    // nearly still one's beyond float, where the reduced clock of a negative phase overflowed).
    if (!(period <= std::fabs(t))) return float(t);
    return float(t - period * std::floor(t / period));
}

}  // namespace

World::World(const LoadedScene& scene) : source_(scene) {
    scene_.blases = scene.scene.blases;
    scene_.materials = scene.scene.materials;
    scene_.pbrMaterials = scene.scene.pbrMaterials;
    scene_.lights = scene.scene.lights;
    scene_.textures = scene.scene.textures;
    scene_.texels = scene.scene.texels;
    scene_.camera = scene.scene.camera;
    scene_.background = scene.scene.background;
    scene_.maxDepth = scene.scene.maxDepth;
    scene_.deformableMeshes = scene.scene.deformableMeshes;
    physics::AddPhysicsAnimSystems(scheduler_, physics_, transforms_);
    SpawnDue(0.0, 0.0);
    transforms_.Update(registry_);
    physics::UpdateSkins(registry_);
    Extract();
    deformChanged_.swap(deformPending_);
    ExtractPoses();
    topologyPending_ = false;
}

void World::SpawnDue(double pendingDt, double bodiesDueBy) {
    const std::vector<EntityDesc>& entities = source_.entities;
    const size_t first = nextSpawn_;
    for (; nextSpawn_ < entities.size() && entities[nextSpawn_].spawnTime <= time_; ++nextSpawn_) {
        const EntityDesc& d = entities[nextSpawn_];
        if (d.body && double(d.spawnTime) > bodiesDueBy) break;
        created_.push_back(Create(d));
        // Its animation and deformation run from the time it is due, not from the frame that
        // finds it due, so that its pose at a given time does not depend on the frame rate.
        const double late = time_ - double(d.spawnTime) - pendingDt;
        if (auto* animator = registry_.Get<physics::Animator>(created_.back()))
            animator->time += double(animator->speed) * late;
        if (auto* link = registry_.Get<DeformationLink>(created_.back()))
            link->born = double(d.spawnTime);
        // Parents come first (FinishLoadedScene keeps them so): the link never closes a cycle.
        if (d.parent >= 0) physics::SetParent(registry_, created_.back(), created_[d.parent]);
    }
    // Joints may come after the mesh they bend: skins are attached once the batch exists.
    for (size_t i = first; i < nextSpawn_; ++i) AttachPose(entities[i], created_[i], created_);
}

void World::AttachPose(const EntityDesc& d, ecs::Entity e, std::span<const ecs::Entity> batch) {
    if (!d.renderable || d.deformableMesh < 0) return;
    auto entityAt = [&](int32_t index) {
        return index >= 0 && size_t(index) < batch.size() ? batch[size_t(index)] : ecs::Entity{};
    };
    if (d.skin && !batch.empty()) {
        physics::Skin skin;
        for (int32_t joint : d.skin->joints) skin.joints.push_back(entityAt(joint));
        skin.inverseBind = d.skin->inverseBind;
        registry_.Add(e, std::move(skin));
    }
    if (d.morph)
        registry_.Add(e, physics::MorphWeights{d.morph->weights, entityAt(d.morph->animator)});
}

// Copies the skins and morph weights that changed into their entities' Deformation records.
void World::ExtractPoses() {
    registry_.EachChanged<physics::Skin>([&](ecs::Entity e, physics::Skin& skin) {
        const DeformationLink* link = registry_.Get<DeformationLink>(e);
        if (!link) return;
        Deformation& d = scene_.deformations[link->deformation];
        if (skin.jointMatrices.size() != d.jointMatrices.size()) return;
        for (size_t j = 0; j < d.jointMatrices.size(); ++j)
            d.jointMatrices[j] = AffineFromMat4(skin.jointMatrices[j]);
        deformChanged_.push_back(link->deformation);
    });
    registry_.ClearChanged<physics::Skin>();
    registry_.EachChanged<physics::MorphWeights>([&](ecs::Entity e, physics::MorphWeights& m) {
        const DeformationLink* link = registry_.Get<DeformationLink>(e);
        if (!link) return;
        Deformation& d = scene_.deformations[link->deformation];
        if (m.weights.size() != d.morphWeights.size()) return;
        d.morphWeights = m.weights;
        deformChanged_.push_back(link->deformation);
    });
    registry_.ClearChanged<physics::MorphWeights>();
    // A record can change by its pose and its procedural clock in one frame: listed once.
    std::sort(deformChanged_.begin(), deformChanged_.end());
    deformChanged_.erase(std::unique(deformChanged_.begin(), deformChanged_.end()),
                         deformChanged_.end());
}

ecs::Entity World::Create(const EntityDesc& d) {
    const ecs::Entity e = registry_.Create();
    registry_.Add(e, d.local);
    if (d.renderable && d.deformableMesh >= 0) {
        const uint32_t deformation = AcquireDeformation(d);
        ProceduralDeform& procedural = scene_.deformations[deformation].procedural;
        procedural = d.procedural;
        procedural.time = DeformClock(procedural, double(d.procedural.time));
        registry_.Add(e, Renderable{scene_.deformations[deformation].blasId, d.materialId});
        registry_.Add(e, DeformationLink{deformation, d.procedural.time, time_});
        deformPending_.push_back(deformation);
    } else if (d.renderable) {
        registry_.Add(e, Renderable{d.blasId, d.materialId});
    }
    if (d.animator) registry_.Add(e, *d.animator);
    if (d.body) {
        registry_.Add(e, *d.body);
        registry_.Add(e, d.collider);
    }
    topologyPending_ = true;
    return e;
}

uint32_t World::AcquireDeformation(const EntityDesc& d) {
    for (size_t k = 0; k < freeDeformations_.size(); ++k) {
        const uint32_t candidate = freeDeformations_[k];
        const Deformation& def = scene_.deformations[candidate];
        if (def.mesh == uint32_t(d.deformableMesh) &&
            scene_.blases[def.blasId] == scene_.blases[d.blasId]) {
            freeDeformations_.erase(freeDeformations_.begin() + k);
            // The last owner's pose goes: the new entity starts from the mesh's rest pose.
            Deformation& reused = scene_.deformations[candidate];
            const DeformableMesh& mesh = *scene_.deformableMeshes[reused.mesh];
            reused.procedural = {};
            reused.jointMatrices.assign(mesh.jointCount, Affine::Identity());
            reused.morphWeights = mesh.defaultWeights;
            return candidate;
        }
    }
    return scene_.AddDeformation(uint32_t(d.deformableMesh), d.blasId);
}

// Procedural deformations follow the clock; a paused frame (dt = 0) changes none.
void World::AdvanceDeformations() {
    registry_.View<DeformationLink>().Each([&](ecs::Entity, DeformationLink& link) {
        ProceduralDeform& p = scene_.deformations[link.deformation].procedural;
        if (p.kind == ProceduralDeformKind::kNone) return;
        const float t = DeformClock(p, double(link.phase) + (time_ - link.born));
        if (p.time == t) return;
        p.time = t;
        deformChanged_.push_back(link.deformation);
    });
}

uint32_t World::AddBlas(std::shared_ptr<const Blas> blas) {
    return scene_.AddBlas(std::move(blas));
}

uint32_t World::AddMaterial(const Material& material) { return scene_.AddMaterial(material); }

uint32_t World::AddPbrMaterial(const Material& approximation, const PbrMaterial& pbr) {
    return scene_.AddPbrMaterial(approximation, pbr);
}

ecs::Entity World::Spawn(const EntityDesc& desc) {
    const ecs::Entity e = Create(desc);
    AttachPose(desc, e, {});
    return e;
}

ecs::Entity World::SpawnGroup(std::span<const EntityDesc> group) {
    std::vector<ecs::Entity> made;
    for (const EntityDesc& d : group) {
        made.push_back(Create(d));
        if (d.parent >= 0 && size_t(d.parent) < made.size() - 1)
            physics::SetParent(registry_, made.back(), made[size_t(d.parent)]);
    }
    for (size_t i = 0; i < group.size(); ++i) AttachPose(group[i], made[i], made);
    return made.empty() ? ecs::Entity{} : made.front();
}

uint32_t World::AddDeformableMesh(std::shared_ptr<const DeformableMesh> mesh) {
    return scene_.AddDeformableMesh(std::move(mesh));
}

uint32_t World::AddTexture(const Texture& texture, const uint32_t* rgba) {
    return scene_.AddTexture(texture, rgba);
}

bool World::SetPose(ecs::Entity e, vec3 position, glm::quat rotation) {
    physics::LocalTransform* local = registry_.Get<physics::LocalTransform>(e);
    if (!local) return false;
    // What slept on it falls once it is moved away (a static body's next step finds it moved and
    // does this itself; a teleported dynamic one does not).
    physics::WakeSleepersAround(registry_, e, physics_.Settings().contactMargin);
    local->translation = position;
    local->rotation = rotation;
    registry_.MarkChanged<physics::LocalTransform>(e);
    // An animated one keeps the edit as its animator's placement, or the next frame's pose would
    // put it back.
    if (physics::Animator* animator = registry_.Get<physics::Animator>(e))
        physics::PlaceAnimated(*animator, position, rotation);
    // A dynamic body is moved at once; a static one keeps the pose the last step saw, so that
    // the world finds it moved and wakes the sleepers it is moved into.
    physics::RigidBody* body = registry_.Get<physics::RigidBody>(e);
    const physics::Collider* collider = registry_.Get<physics::Collider>(e);
    const bool dynamic = body && body->mass > 0.0f &&
                         !(collider && collider->shape == physics::ColliderShape::kPlane);
    if (dynamic) {
        physics::Teleport(*body, position, rotation);
        body->velocity = body->angularVelocity = vec3(0.0f);
    }
    return true;
}

ecs::Entity World::ObjectRoot(ecs::Entity e) const {
    if (!registry_.Valid(e)) return {};
    ecs::Entity root = e;
    // At most one hop per parent link: a cycle (see RemoveObject) ends somewhere on it.
    for (size_t hops = 0; hops < registry_.Count<physics::Parent>(); ++hops) {
        const physics::Parent* up = registry_.Get<physics::Parent>(root);
        if (!up || !registry_.Valid(up->entity)) break;
        root = up->entity;
    }
    return root;
}

bool World::RemoveObject(ecs::Entity e) {
    if (!registry_.Valid(e)) return false;
    // Up to the root of its hierarchy, then everything under it.
    const ecs::Entity root = ObjectRoot(e);
    // Breadth first over the parent links, each entity once: two SetParent calls in one
    // deferred phase can close a cycle (the transform system tolerates it), which had made this
    // walk grow without end.
    std::unordered_map<uint32_t, std::vector<ecs::Entity>> children;  // by the parent's index
    registry_.View<const physics::Parent>().Each(
        [&](ecs::Entity child, const physics::Parent& link) {
            if (registry_.Valid(link.entity)) children[link.entity.index].push_back(child);
        });
    std::unordered_set<uint32_t> seen{root.index};
    std::vector<ecs::Entity> doomed{root};
    for (size_t i = 0; i < doomed.size(); ++i) {
        const auto found = children.find(doomed[i].index);
        if (found == children.end()) continue;
        for (const ecs::Entity child : found->second)
            if (seen.insert(child.index).second) doomed.push_back(child);
    }
    for (const ecs::Entity d : doomed) {
        if (!Remove(d) && registry_.Valid(d)) {
            physics::WakeSleepersAround(registry_, d, physics_.Settings().contactMargin);
            registry_.Destroy(d);
            topologyPending_ = true;
        }
    }
    return true;
}

bool World::Remove(ecs::Entity e) {
    const Renderable* r = registry_.Get<Renderable>(e);
    if (!r) return false;
    const uint32_t slot = r->instance;
    if (slot != UINT32_MAX) {
        const uint32_t last = uint32_t(scene_.instances.size() - 1);
        if (slot != last) {
            scene_.instances[slot] = scene_.instances[last];
            instanceOwner_[slot] = instanceOwner_[last];
            registry_.Get<Renderable>(instanceOwner_[slot])->instance = slot;
        }
        scene_.instances.pop_back();
        instanceOwner_.pop_back();
    }
    if (const DeformationLink* link = registry_.Get<DeformationLink>(e))
        freeDeformations_.push_back(link->deformation);
    physics::WakeSleepersAround(registry_, e, physics_.Settings().contactMargin);
    registry_.Destroy(e);
    topologyPending_ = true;
    return true;
}

void World::OverrideCamera(const Camera& camera) {
    cameraOverride_ = camera;
    scene_.camera = camera;
}

bool World::HasPhysics() const {
    for (const EntityDesc& d : source_.entities)
        if (d.body) return true;
    return false;
}

ecs::Entity World::EntityOfInstance(uint32_t instance) const {
    return instance < instanceOwner_.size() ? instanceOwner_[instance] : ecs::Entity{};
}

// Rewrites the instance records of the entities whose world transform changed.
uint32_t World::Extract() {
    uint32_t extracted = 0;
    registry_.EachChanged<physics::WorldTransform>([&](ecs::Entity e, physics::WorldTransform& w) {
        Renderable* r = registry_.Get<Renderable>(e);
        if (!r) return;
        // A skinned mesh is posed by its joints alone (skinning.h).
        const glm::mat4 placement = registry_.Get<physics::Skin>(e) != nullptr
                                        ? physics::SkinnedMeshFrame(w.objectToWorld)
                                        : w.objectToWorld;
        if (r->instance == UINT32_MAX) {
            r->instance = scene_.AddInstance(r->blasId, r->materialId, placement);
            instanceOwner_.push_back(e);
            changed_.push_back(r->instance);
        } else {
            Instance& inst = scene_.instances[r->instance];
            SetTransform(inst, placement);
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
    deformChanged_.clear();
    const size_t before = nextSpawn_;
    Stopwatch timer;
    // A rigid body due inside the frame joins the simulation at its time, not at the frame's
    // start: the frame is simulated in parts split at those times, so that a body's path does
    // not depend on the frame rate (animations are shifted instead, in SpawnDue).
    const double frameEnd = time_ + double(dt);
    for (double start = time_;;) {
        double end = frameEnd;
        for (size_t k = nextSpawn_; k < source_.entities.size(); ++k) {
            const double due = source_.entities[k].spawnTime;
            if (due >= frameEnd) break;
            if (source_.entities[k].body && due > start) {
                end = due;
                break;
            }
        }
        time_ = end;
        SpawnDue(end - start, start);
        scheduler_.RunFrame(registry_, float(end - start));
        if (end >= frameEnd) break;
        start = end;
    }
    // Bodies due at the frame's very end appear in it, where they are due, posed as the
    // constructor poses the first frame's.
    const size_t beforeEnd = nextSpawn_;
    SpawnDue(0.0, frameEnd);
    if (nextSpawn_ != beforeEnd) {
        transforms_.Update(registry_);
        physics::UpdateSkins(registry_);
    }
    stats.spawned = uint32_t(nextSpawn_ - before);
    stats.simulateMs = timer.Milliseconds();
    timer.Restart();
    stats.extracted = Extract();
    AdvanceDeformations();
    // Deformations created since the last Advance (edits, this frame's spawns) are new now.
    deformChanged_.insert(deformChanged_.end(), deformPending_.begin(), deformPending_.end());
    deformPending_.clear();
    ExtractPoses();
    stats.extractMs = timer.Milliseconds();
    topologyChanged_ = topologyPending_;
    topologyPending_ = false;
    scene_.camera = cameraOverride_ ? *cameraOverride_ : CameraAt(source_, time_);
    return stats;
}

}  // namespace rtrt
