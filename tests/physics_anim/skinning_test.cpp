// Skins and morph weights: a two-bone cylinder bent at known angles against the closed form of a
// rotation about the knee, weights blended at the knee ring, joint matrices in the mesh's frame
// (its world, or its position where that has no inverse) recomputed only when a joint or the
// mesh moved; morphs at known weights,
// animated by their animator's weights track.
#include "engine/physics_anim/skinning.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/physics_anim/animator.h"
#include "engine/physics_anim/physics_anim_systems.h"
#include "engine/physics_anim/physics_world.h"
#include "engine/physics_anim/transform_system.h"

namespace rtrt::physics {
namespace {

using ecs::Entity;
using ecs::Registry;

constexpr float kTolerance = 2e-6f;

void ExpectNear(vec3 actual, vec3 expected, const char* what) {
    EXPECT_NEAR(actual.x, expected.x, kTolerance) << what;
    EXPECT_NEAR(actual.y, expected.y, kTolerance) << what;
    EXPECT_NEAR(actual.z, expected.z, kTolerance) << what;
}

// A cylinder of radius 0.25 along +y from 0 to 2 under a root turned and moved in the world; the
// hip joint sits at the root's origin, the knee joint 1 above it. Bind pose: straight, so the
// inverse bind matrices undo each joint's rest offset (identity, translate(0, -1, 0)).
struct TwoBoneRig {
    Registry registry;
    TransformSystem transforms;
    Entity root, hip, knee, mesh;

    TwoBoneRig() {
        root = Node(LocalTransform{vec3(5.0f, 0.0f, -2.0f),
                                   glm::angleAxis(glm::radians(30.0f), vec3(0, 1, 0))});
        hip = Node(LocalTransform{});
        knee = Node(LocalTransform{vec3(0.0f, 1.0f, 0.0f)});
        mesh = Node(LocalTransform{});
        SetParent(registry, hip, root);
        SetParent(registry, knee, hip);
        SetParent(registry, mesh, root);
        Skin skin;
        skin.joints = {hip, knee};
        skin.inverseBind = {glm::mat4(1.0f),
                            glm::translate(glm::mat4(1.0f), vec3(0.0f, -1.0f, 0.0f))};
        registry.Add(mesh, skin);
        Update();
    }
    Entity Node(LocalTransform local) {
        const Entity e = registry.Create();
        registry.Add(e, local);
        return e;
    }
    // One frame: transforms, skins, then what extraction would do with the marks.
    uint32_t Update() {
        transforms.Update(registry);
        const uint32_t skinned = UpdateSkins(registry);
        registry.ClearChanged<WorldTransform>();
        registry.ClearChanged<Skin>();
        return skinned;
    }
    void BendKnee(float degrees) {
        registry.Get<LocalTransform>(knee)->rotation =
            glm::angleAxis(glm::radians(degrees), vec3(0, 0, 1));
        registry.MarkChanged<LocalTransform>(knee);
    }
    const std::vector<glm::mat4>& JointMatrices() {
        return registry.Get<Skin>(mesh)->jointMatrices;
    }
    // Where a skinned position lands in the world (the instance transform places the mesh's
    // frame), and where a position of the mesh's own space does.
    vec3 FromFrame(vec3 skinned) {
        const glm::mat4 meshWorld = registry.Get<WorldTransform>(mesh)->objectToWorld;
        return vec3(SkinnedMeshFrame(meshWorld) * glm::vec4(skinned, 1.0f));
    }
    glm::mat3 FrameRotation() {
        return glm::mat3(SkinnedMeshFrame(registry.Get<WorldTransform>(mesh)->objectToWorld));
    }
    vec3 FromMesh(vec3 local) {
        return vec3(registry.Get<WorldTransform>(mesh)->objectToWorld * glm::vec4(local, 1.0f));
    }
};

// A vertex above the knee follows the knee alone: bent by theta about z through (0, 1, 0),
// x' = x cos - (y - 1) sin, y' = 1 + x sin + (y - 1) cos, z' = z.
vec3 BentAboutKnee(vec3 p, float theta) {
    return vec3(p.x * std::cos(theta) - (p.y - 1.0f) * std::sin(theta),
                1.0f + p.x * std::sin(theta) + (p.y - 1.0f) * std::cos(theta), p.z);
}

TEST(SkinningTest, TwoBoneCylinderBentAtKnownAnglesMatchesTheClosedForm) {
    TwoBoneRig rig;
    const uint32_t hipOnly[] = {0, 0}, kneeOnly[] = {1, 0}, both[] = {0, 1};
    const float rigid[] = {1.0f, 0.0f}, half[] = {0.5f, 0.5f};
    for (float degrees : {0.0f, 30.0f, 90.0f, -135.0f}) {
        rig.BendKnee(degrees);
        EXPECT_EQ(rig.Update(), 1u);
        const float theta = glm::radians(degrees);
        const std::vector<glm::mat4>& m = rig.JointMatrices();
        for (int ring = 0; ring <= 8; ++ring) {
            const float y = 0.25f * float(ring);
            for (int step = 0; step < 6; ++step) {
                const float a = float(step) * glm::radians(60.0f);
                const vec3 p(0.25f * std::cos(a), y, 0.25f * std::sin(a));
                if (y < 1.0f) {  // the thigh: the hip never turns
                    ExpectNear(rig.FromFrame(SkinnedPosition(p, hipOnly, rigid, m)),
                               rig.FromMesh(p), "thigh");
                } else if (y > 1.0f) {
                    ExpectNear(rig.FromFrame(SkinnedPosition(p, kneeOnly, rigid, m)),
                               rig.FromMesh(BentAboutKnee(p, theta)), "shin");
                } else {  // the knee ring, half each: the mean of straight and bent
                    const vec3 expected(0.5f * p.x * (1.0f + std::cos(theta)),
                                        1.0f + 0.5f * p.x * std::sin(theta), p.z);
                    ExpectNear(rig.FromFrame(SkinnedPosition(p, both, half, m)),
                               rig.FromMesh(expected), "knee");
                }
            }
        }
        // Normals turn with the shin (and the rig's root, 30 degrees about y), unit length.
        const vec3 shinNormal = glm::angleAxis(glm::radians(30.0f), vec3(0, 1, 0)) *
                                vec3(std::cos(theta), std::sin(theta), 0.0f);
        ExpectNear(rig.FrameRotation() * SkinnedNormal(vec3(1, 0, 0), kneeOnly, rigid, m),
                   shinNormal, "shin normal");
    }
}

TEST(SkinningTest, JointMatricesAreInTheMeshFrameSoMovingTheWholeRigChangesNone) {
    TwoBoneRig rig;
    rig.BendKnee(45.0f);
    rig.Update();
    const std::vector<glm::mat4> before = rig.JointMatrices();
    // A static frame recomputes no skin.
    EXPECT_EQ(rig.Update(), 0u);
    // Moving the root moves mesh and joints alike: the skin is recomputed, to the same matrices
    // (the world placement is the mesh instance's), and the world position is the frame's.
    rig.registry.Get<LocalTransform>(rig.root)->translation = vec3(-7.0f, 3.0f, 1.0f);
    rig.registry.MarkChanged<LocalTransform>(rig.root);
    EXPECT_EQ(rig.Update(), 1u);
    for (size_t j = 0; j < before.size(); ++j)
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                EXPECT_NEAR(rig.JointMatrices()[j][c][r], before[j][c][r], 1e-5f);
    // The spec's world position of a shin vertex, jointWorld * inverseBind * p, equals the mesh
    // frame applied to the skinned position.
    const vec3 p(0.25f, 2.0f, 0.0f);
    const glm::mat4 kneeWorld = rig.registry.Get<WorldTransform>(rig.knee)->objectToWorld;
    const glm::mat4 meshWorld = rig.registry.Get<WorldTransform>(rig.mesh)->objectToWorld;
    const vec3 spec =
        vec3(kneeWorld * rig.registry.Get<Skin>(rig.mesh)->inverseBind[1] * glm::vec4(p, 1.0f));
    const uint32_t kneeOnly[] = {1};
    const float rigid[] = {1.0f};
    const vec3 skinned = SkinnedPosition(p, kneeOnly, rigid, rig.JointMatrices());
    const vec3 viaFrame = vec3(SkinnedMeshFrame(meshWorld) * glm::vec4(skinned, 1.0f));
    EXPECT_NEAR(glm::length(viaFrame - spec), 0.0f, 1e-5f);
}

// A mesh node scaled flat, which glTF ignores for a skinned mesh, has no inverse: the frame is its
// position alone, and the skinned world position is still jointWorld * inverseBind * p.
TEST(SkinningTest, AMeshNodeWithoutAnInverseIsPlacedByItsPositionAlone) {
    TwoBoneRig rig;
    rig.registry.Get<LocalTransform>(rig.mesh)->scale = vec3(1.0f, 0.0f, 1.0f);
    rig.registry.MarkChanged<LocalTransform>(rig.mesh);
    rig.BendKnee(60.0f);
    rig.Update();
    const glm::mat4 meshWorld = rig.registry.Get<WorldTransform>(rig.mesh)->objectToWorld;
    const glm::mat4 frame = SkinnedMeshFrame(meshWorld);
    EXPECT_EQ(glm::mat3(frame), glm::mat3(1.0f));
    EXPECT_EQ(vec3(frame[3]), vec3(meshWorld[3]));
    const vec3 p(0.25f, 2.0f, 0.0f);
    const glm::mat4 kneeWorld = rig.registry.Get<WorldTransform>(rig.knee)->objectToWorld;
    const vec3 spec =
        vec3(kneeWorld * rig.registry.Get<Skin>(rig.mesh)->inverseBind[1] * glm::vec4(p, 1.0f));
    const uint32_t kneeOnly[] = {1};
    const float rigid[] = {1.0f};
    ExpectNear(rig.FromFrame(SkinnedPosition(p, kneeOnly, rigid, rig.JointMatrices())), spec,
               "flat mesh node");
}

TEST(SkinningTest, OnlyTheMovedJointsSkinIsRecomputedAndMarked) {
    TwoBoneRig rig;
    rig.BendKnee(10.0f);
    rig.transforms.Update(rig.registry);
    EXPECT_EQ(UpdateSkins(rig.registry), 1u);
    EXPECT_EQ(rig.registry.ChangedCount<Skin>(), 1u);
}

// A skinned mesh created between frames (a spawn) has its joint matrices after the first frame the
// scheduler runs: the skins had run in the transforms' phase, before the WorldTransforms of new
// entities were added, and the mesh kept its rest pose for a frame.
TEST(SkinningTest, ASkinCreatedBetweenFramesIsPosedInTheNextFrame) {
    Registry registry;
    PhysicsWorld physics;
    TransformSystem transforms;
    ecs::Scheduler scheduler;
    AddPhysicsAnimSystems(scheduler, physics, transforms);
    const Entity joint = registry.Create();
    registry.Add(joint, LocalTransform{vec3(0.0f, 2.0f, 0.0f)});
    const Entity mesh = registry.Create();
    registry.Add(mesh, LocalTransform{});
    Skin skin;
    skin.joints = {joint};
    skin.inverseBind = {glm::mat4(1.0f)};
    registry.Add(mesh, skin);
    scheduler.RunFrame(registry, 1.0f / 60.0f);
    const std::vector<glm::mat4>& matrices = registry.Get<Skin>(mesh)->jointMatrices;
    ASSERT_EQ(matrices.size(), 1u);
    ExpectNear(vec3(matrices[0][3]), vec3(0.0f, 2.0f, 0.0f), "joint matrix's translation");
    EXPECT_TRUE(registry.IsChanged<Skin>(mesh));
}

TEST(MorphTest, MorphAtKnownWeightsAddsTheWeightedDeltas) {
    const vec3 deltas[] = {vec3(1, 0, 0), vec3(0, 2, 0), vec3(0, 0, -4)};
    const float weights[] = {0.25f, 0.5f, -0.5f};
    // (1, 2, 3) + 0.25 (1, 0, 0) + 0.5 (0, 2, 0) - 0.5 (0, 0, -4) = (1.25, 3, 5).
    ExpectNear(MorphedPosition(vec3(1, 2, 3), deltas, weights), vec3(1.25f, 3.0f, 5.0f), "morph");
    const float none[] = {0.0f, 0.0f, 0.0f};
    ExpectNear(MorphedPosition(vec3(1, 2, 3), deltas, none), vec3(1, 2, 3), "rest");
}

TEST(MorphTest, WeightsFollowTheirAnimatorsTrackAndAreMarkedOnlyWhenTheyChange) {
    Registry registry;
    auto clip = std::make_shared<KeyframeClip>();
    clip->weights.count = 2;
    clip->weights.times = {0.0f, 2.0f};
    clip->weights.values = {0.0f, 0.0f, 1.0f, 0.5f};
    clip->wrap = WrapMode::kClamp;
    const Entity node = registry.Create();
    registry.Add(node, LocalTransform{});
    Animator animator;
    animator.clip = clip;
    registry.Add(node, animator);
    const Entity mesh = registry.Create();
    registry.Add(mesh, MorphWeights{{0.0f, 0.0f}, node});
    registry.ClearChanged<MorphWeights>();
    AnimateEntities(registry, 1.0f);
    EXPECT_EQ(AnimateMorphWeights(registry), 1u);
    EXPECT_EQ(registry.Get<MorphWeights>(mesh)->weights, (std::vector<float>{0.5f, 0.25f}));
    EXPECT_TRUE(registry.IsChanged<MorphWeights>(mesh));
    registry.ClearChanged<MorphWeights>();
    AnimateEntities(registry, 5.0f);  // clamped at the end
    EXPECT_EQ(AnimateMorphWeights(registry), 1u);
    EXPECT_EQ(registry.Get<MorphWeights>(mesh)->weights, (std::vector<float>{1.0f, 0.5f}));
    registry.ClearChanged<MorphWeights>();
    AnimateEntities(registry, 1.0f);  // still at the end: nothing changes
    EXPECT_EQ(AnimateMorphWeights(registry), 0u);
    EXPECT_FALSE(registry.IsChanged<MorphWeights>(mesh));
    // A paused animator leaves the weights alone.
    registry.Get<Animator>(node)->playing = false;
    registry.Get<MorphWeights>(mesh)->weights = {0.0f, 0.0f};
    EXPECT_EQ(AnimateMorphWeights(registry), 0u);
}

}  // namespace
}  // namespace rtrt::physics
