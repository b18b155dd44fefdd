#include "engine/physics_anim/skinning.h"

#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>
#include <vector>

#include "engine/core/parallel_for.h"
#include "engine/physics_anim/animator.h"

namespace rtrt::physics {

glm::mat4 SkinnedMeshFrame(const glm::mat4& meshWorld) {
    // Usable: axes of lengths a float inverse keeps (1e-6 to 1e6; a scale of 1e-20 is not) that
    // are not flattened together (the determinant against their lengths' product), in double.
    const glm::dmat3 linear(meshWorld);
    const double lengths[3] = {glm::length(linear[0]), glm::length(linear[1]),
                               glm::length(linear[2])};
    bool usable = true;
    for (const double length : lengths) usable = usable && length >= 1e-6 && length <= 1e6;
    const double det = glm::determinant(linear);
    if (usable && std::fabs(det) > 1e-6 * lengths[0] * lengths[1] * lengths[2]) return meshWorld;
    glm::mat4 frame(1.0f);
    frame[3] = glm::vec4(glm::vec3(meshWorld[3]), 1.0f);
    return frame;
}

glm::mat4 JointMatrix(const glm::mat4& toMeshFrame, const glm::mat4& jointWorld,
                      const glm::mat4& inverseBind) {
    return toMeshFrame * jointWorld * inverseBind;
}

vec3 SkinnedPosition(vec3 rest, std::span<const uint32_t> joints, std::span<const float> weights,
                     std::span<const glm::mat4> jointMatrices) {
    vec3 p(0.0f);
    for (size_t i = 0; i < joints.size(); ++i)
        if (weights[i] != 0.0f)
            p += weights[i] * vec3(jointMatrices[joints[i]] * glm::vec4(rest, 1.0f));
    return p;
}

vec3 SkinnedNormal(vec3 rest, std::span<const uint32_t> joints, std::span<const float> weights,
                   std::span<const glm::mat4> jointMatrices) {
    vec3 n(0.0f);
    for (size_t i = 0; i < joints.size(); ++i)
        if (weights[i] != 0.0f)
            n += weights[i] * (glm::inverseTranspose(glm::mat3(jointMatrices[joints[i]])) * rest);
    const float length = glm::length(n);
    return length > 0.0f ? n / length : rest;
}

vec3 MorphedPosition(vec3 rest, std::span<const vec3> deltas, std::span<const float> weights) {
    for (size_t t = 0; t < deltas.size(); ++t) rest += weights[t] * deltas[t];
    return rest;
}

uint32_t UpdateSkins(ecs::Registry& registry) {
    struct Candidate {
        ecs::Entity entity;
        Skin* skin;
        const WorldTransform* mesh;
        bool moved;
    };
    std::vector<Candidate> skins;
    registry.View<Skin, const WorldTransform>().Each(
        [&](ecs::Entity e, Skin& skin, const WorldTransform& mesh) {
            skins.push_back({e, &skin, &mesh, false});
        });
    // Skins are independent and only read the registry here: in parallel, marked after.
    const ecs::Registry& reader = registry;
    ParallelFor(0, skins.size(), 16, [&](size_t i) {
        Candidate& c = skins[i];
        Skin& skin = *c.skin;
        bool moved = skin.jointMatrices.size() != skin.joints.size() ||
                     reader.IsChanged<WorldTransform>(c.entity);
        for (size_t j = 0; j < skin.joints.size() && !moved; ++j)
            moved = reader.IsChanged<WorldTransform>(skin.joints[j]);
        if (!moved) return;
        skin.jointMatrices.resize(skin.joints.size(), glm::mat4(1.0f));
        const glm::mat4 toMeshFrame = glm::affineInverse(SkinnedMeshFrame(c.mesh->objectToWorld));
        for (size_t j = 0; j < skin.joints.size(); ++j)
            if (const WorldTransform* joint = reader.Get<WorldTransform>(skin.joints[j]))
                skin.jointMatrices[j] =
                    JointMatrix(toMeshFrame, joint->objectToWorld, skin.inverseBind[j]);
        c.moved = true;
    });
    uint32_t updated = 0;
    for (const Candidate& c : skins)
        if (c.moved) {
            registry.MarkChanged<Skin>(c.entity);
            ++updated;
        }
    return updated;
}

uint32_t AnimateMorphWeights(ecs::Registry& registry) {
    uint32_t changed = 0;
    std::vector<float> sampled;
    registry.View<MorphWeights>().Each([&](ecs::Entity e, MorphWeights& morph) {
        const Animator* animator = registry.Get<Animator>(morph.animator);
        if (!animator || !animator->playing || !animator->clip) return;
        const KeyframeClip& clip = *animator->clip;
        if (clip.weights.Empty() || clip.weights.count != morph.weights.size()) return;
        sampled.resize(morph.weights.size());
        SampleTrack(clip.weights, ClipTime(clip, animator->time), sampled);
        if (sampled == morph.weights) return;
        morph.weights = sampled;
        registry.MarkChanged<MorphWeights>(e);
        ++changed;
    });
    return changed;
}

void AddMorphWeightsSystem(ecs::Scheduler& scheduler) {
    scheduler.AddSystem("animation", "morph weights",
                        [](ecs::Registry& registry, float) { AnimateMorphWeights(registry); });
}

void AddSkinSystem(ecs::Scheduler& scheduler) {
    scheduler.AddSystem("extraction", "skins",
                        [](ecs::Registry& registry, float) { UpdateSkins(registry); });
}

}  // namespace rtrt::physics
