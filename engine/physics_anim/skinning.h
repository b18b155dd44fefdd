#pragma once
// Skins and morph weights as components: what poses a deforming mesh entity, derived each frame
// from its joints' world transforms and its animator's weights track. The frame renderer deforms
// the mesh from what these hold (the runtime copies them into Deformation records).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/ecs/registry.h"
#include "engine/ecs/scheduler.h"
#include "engine/physics_anim/transform.h"

namespace rtrt::physics {

// A skinned mesh entity's joints (entities of the hierarchy, posed like any other) and their
// inverse bind matrices. jointMatrices is derived (UpdateSkins): one per joint, from the mesh's
// rest space to its deformed space (JointMatrix).
struct Skin {
    std::vector<ecs::Entity> joints;
    std::vector<glm::mat4> inverseBind;  // one per joint
    std::vector<glm::mat4> jointMatrices;
};

// A morphing mesh entity's weights, one per morph target. When `animator` names an entity with
// an Animator whose clip has a weights track, that track at the animator's time poses them (so
// every primitive of a glTF node follows its node's clock, and each instance its own); else
// they stay as set.
struct MorphWeights {
    std::vector<float> weights;
    ecs::Entity animator;
};

// Where a skinned mesh's instance is placed: its node's world transform, so that the deformed
// mesh stays in the orientation its rest tree was built in (refits stay tight); but only its
// position when that transform has no usable inverse (a node scaled to 0, or by 1e-20), which
// glTF allows, since it ignores a skinned mesh node's transform (the joints alone pose the mesh).
glm::mat4 SkinnedMeshFrame(const glm::mat4& meshWorld);

// glTF 2.0 skinning: toMeshFrame * jointWorld * inverseBind, toMeshFrame being
// inverse(SkinnedMeshFrame(meshWorld)) (the same for every joint of a skin). Applied to a rest
// position it gives the skinned position in the mesh's frame, which the instance transform (that
// frame) then places: together jointWorld * inverseBind, the spec's world position.
glm::mat4 JointMatrix(const glm::mat4& toMeshFrame, const glm::mat4& jointWorld,
                      const glm::mat4& inverseBind);

// Linear blend skinning of one vertex: sum over its influences of weight * (joint matrix * p).
// joints and weights are the vertex's influences (as many of each); weights sum to 1.
vec3 SkinnedPosition(vec3 rest, std::span<const uint32_t> joints, std::span<const float> weights,
                     std::span<const glm::mat4> jointMatrices);
// The same for a normal: blended by the matrices' inverse transposes, then normalised.
vec3 SkinnedNormal(vec3 rest, std::span<const uint32_t> joints, std::span<const float> weights,
                   std::span<const glm::mat4> jointMatrices);
// Morphing one vertex: rest + sum over targets of weight * delta (one delta per target).
vec3 MorphedPosition(vec3 rest, std::span<const vec3> deltas, std::span<const float> weights);

// Recomputes the joint matrices of every skin whose mesh entity's or any joint's WorldTransform
// is marked changed this frame (or that has none yet) and marks its Skin changed. A joint that
// no longer exists keeps its last matrix. Returns how many skins were recomputed.
uint32_t UpdateSkins(ecs::Registry& registry);

// Samples the weights track of each MorphWeights' animator at its time; marks MorphWeights
// changed where a weight differs from what it held. Returns how many changed.
uint32_t AnimateMorphWeights(ecs::Registry& registry);

// Adds AnimateMorphWeights ("morph weights") to phase "animation"; call after the animation
// system, which advances the animators' time.
void AddMorphWeightsSystem(ecs::Scheduler& scheduler);
// Adds UpdateSkins ("skins") to phase "extraction", after the transform system's phase, whose
// WorldTransforms of new entities are added when it ends.
void AddSkinSystem(ecs::Scheduler& scheduler);

}  // namespace rtrt::physics
