// Transform hierarchy: world = parent world * local, parents before children, cycles rejected,
// only changed entities (and their descendants) recomputed.
#include "engine/physics_anim/transform_system.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace rtrt::physics {
namespace {

using ecs::Entity;
using ecs::Registry;

constexpr float kTolerance = 1e-6f;

vec3 WorldPosition(const Registry& registry, Entity e) {
    return vec3(registry.Get<WorldTransform>(e)->objectToWorld[3]);
}

void ExpectNear(vec3 actual, vec3 expected) {
    EXPECT_NEAR(actual.x, expected.x, kTolerance);
    EXPECT_NEAR(actual.y, expected.y, kTolerance);
    EXPECT_NEAR(actual.z, expected.z, kTolerance);
}

Entity MakeNode(Registry& registry, vec3 translation) {
    const Entity e = registry.Create();
    registry.Add(e, LocalTransform{translation});
    return e;
}

TEST(TransformSystemTest, RootWorldIsItsLocalMatrix) {
    Registry registry;
    const Entity e = registry.Create();
    LocalTransform local;
    local.translation = vec3(1.0f, 2.0f, 3.0f);
    local.scale = vec3(2.0f);
    registry.Add(e, local);
    TransformSystem system;
    system.Update(registry);
    const glm::mat4& m = registry.Get<WorldTransform>(e)->objectToWorld;
    EXPECT_EQ(m, glm::translate(glm::mat4(1.0f), local.translation) *
                     glm::scale(glm::mat4(1.0f), vec3(2.0f)));
}

TEST(TransformSystemTest, ChildFollowsTranslatedRotatedScaledParent) {
    Registry registry;
    const Entity parent = registry.Create();
    LocalTransform parentLocal;
    parentLocal.translation = vec3(1.0f, 0.0f, 0.0f);
    parentLocal.rotation = glm::angleAxis(0.5f * kPi, vec3(0.0f, 1.0f, 0.0f));
    parentLocal.scale = vec3(2.0f);
    registry.Add(parent, parentLocal);
    const Entity child = MakeNode(registry, vec3(0.0f, 0.0f, 1.0f));
    ASSERT_TRUE(SetParent(registry, child, parent));
    TransformSystem system;
    system.Update(registry);
    // Rotating +Z by 90 degrees about +Y gives +X; scaled by 2, offset by the parent's (1, 0, 0).
    ExpectNear(WorldPosition(registry, child), vec3(3.0f, 0.0f, 0.0f));

    registry.Get<LocalTransform>(parent)->translation = vec3(0.0f, 5.0f, 0.0f);
    registry.MarkChanged<LocalTransform>(parent);
    system.Update(registry);
    ExpectNear(WorldPosition(registry, child), vec3(2.0f, 5.0f, 0.0f));
    EXPECT_EQ(system.Stats().lastRecomputed, 2u);  // the parent and, through it, the child
}

// Children created before their parents have lower entity indices: only depth order makes the
// grandchild see this pass's parent world.
TEST(TransformSystemTest, ParentsAreComputedBeforeChildrenWhateverTheCreationOrder) {
    Registry registry;
    const Entity grandchild = MakeNode(registry, vec3(0.0f, 0.0f, 1.0f));
    const Entity child = MakeNode(registry, vec3(0.0f, 1.0f, 0.0f));
    const Entity root = MakeNode(registry, vec3(1.0f, 0.0f, 0.0f));
    ASSERT_TRUE(SetParent(registry, grandchild, child));
    ASSERT_TRUE(SetParent(registry, child, root));
    TransformSystem system;
    system.Update(registry);
    ExpectNear(WorldPosition(registry, grandchild), vec3(1.0f, 1.0f, 1.0f));

    registry.Get<LocalTransform>(root)->translation = vec3(10.0f, 0.0f, 0.0f);
    registry.MarkChanged<LocalTransform>(root);
    system.Update(registry);
    ExpectNear(WorldPosition(registry, child), vec3(10.0f, 1.0f, 0.0f));
    ExpectNear(WorldPosition(registry, grandchild), vec3(10.0f, 1.0f, 1.0f));
}

TEST(TransformSystemTest, SetParentRejectsCycles) {
    Registry registry;
    const Entity a = MakeNode(registry, vec3(0.0f));
    const Entity b = MakeNode(registry, vec3(0.0f));
    const Entity c = MakeNode(registry, vec3(0.0f));
    EXPECT_FALSE(SetParent(registry, a, a));
    EXPECT_TRUE(SetParent(registry, b, a));
    EXPECT_TRUE(SetParent(registry, c, b));
    EXPECT_FALSE(SetParent(registry, a, c));  // a is c's grandparent
    EXPECT_FALSE(SetParent(registry, a, b));
    EXPECT_FALSE(registry.Has<Parent>(a));
    EXPECT_TRUE(SetParent(registry, c, a));  // re-parenting within the tree is fine
    EXPECT_EQ(registry.Get<Parent>(c)->entity, a);
}

TEST(TransformSystemTest, SetParentRejectsDeadEntities) {
    Registry registry;
    const Entity a = MakeNode(registry, vec3(0.0f));
    const Entity b = MakeNode(registry, vec3(0.0f));
    registry.Destroy(b);
    EXPECT_FALSE(SetParent(registry, a, b));
    EXPECT_FALSE(SetParent(registry, b, a));
}

// A cycle made behind SetParent's back (e.g. two links recorded in one deferred phase) must not
// hang the system: its members are treated as roots and reported.
TEST(TransformSystemTest, CycleMadeBehindSetParentsBackIsBrokenAndReported) {
    Registry registry;
    const Entity a = MakeNode(registry, vec3(1.0f, 0.0f, 0.0f));
    const Entity b = MakeNode(registry, vec3(0.0f, 2.0f, 0.0f));
    registry.BeginDeferred();
    EXPECT_TRUE(SetParent(registry, a, b));
    EXPECT_TRUE(SetParent(registry, b, a));
    registry.EndDeferred();
    TransformSystem system;
    system.Update(registry);
    EXPECT_EQ(system.Stats().lastCyclic, 2u);
    ExpectNear(WorldPosition(registry, a), vec3(1.0f, 0.0f, 0.0f));
    ExpectNear(WorldPosition(registry, b), vec3(0.0f, 2.0f, 0.0f));
}

TEST(TransformSystemTest, StaticEntityIsNeverRecomputed) {
    Registry registry;
    const Entity still = MakeNode(registry, vec3(5.0f, 0.0f, 0.0f));
    const Entity mover = MakeNode(registry, vec3(0.0f));
    TransformSystem system;
    system.Update(registry);
    EXPECT_EQ(system.Stats().recomputed, 2u);
    registry.ClearChanged<WorldTransform>();  // what extraction does after reading the changes

    constexpr int kFrames = 100;
    for (int frame = 1; frame <= kFrames; ++frame) {
        registry.Get<LocalTransform>(mover)->translation.x = static_cast<float>(frame);
        registry.MarkChanged<LocalTransform>(mover);
        system.Update(registry);
        EXPECT_EQ(system.Stats().lastRecomputed, 1u);
        ASSERT_EQ(registry.ChangedCount<WorldTransform>(), 1u);
        registry.EachChanged<WorldTransform>(
            [&](Entity e, WorldTransform&) { EXPECT_EQ(e, mover); });
        registry.ClearChanged<WorldTransform>();
    }
    EXPECT_EQ(system.Stats().recomputed, 2u + kFrames);
    ExpectNear(WorldPosition(registry, still), vec3(5.0f, 0.0f, 0.0f));
    ExpectNear(WorldPosition(registry, mover), vec3(100.0f, 0.0f, 0.0f));
}

TEST(TransformSystemTest, NothingChangedMeansNothingRecomputed) {
    Registry registry;
    for (int i = 0; i < 1000; ++i) MakeNode(registry, vec3(static_cast<float>(i)));
    TransformSystem system;
    system.Update(registry);
    EXPECT_EQ(system.Stats().lastRecomputed, 1000u);
    for (int i = 0; i < 10; ++i) system.Update(registry);
    EXPECT_EQ(system.Stats().lastRecomputed, 0u);
    EXPECT_EQ(system.Stats().recomputed, 1000u);
}

TEST(TransformSystemTest, SiblingsOfAMovedChildAreNotRecomputed) {
    Registry registry;
    const Entity root = MakeNode(registry, vec3(0.0f));
    const Entity left = MakeNode(registry, vec3(-1.0f, 0.0f, 0.0f));
    const Entity right = MakeNode(registry, vec3(1.0f, 0.0f, 0.0f));
    const Entity leaf = MakeNode(registry, vec3(0.0f, 1.0f, 0.0f));
    ASSERT_TRUE(SetParent(registry, left, root));
    ASSERT_TRUE(SetParent(registry, right, root));
    ASSERT_TRUE(SetParent(registry, leaf, left));
    TransformSystem system;
    system.Update(registry);
    EXPECT_EQ(system.Stats().lastRecomputed, 4u);
    registry.Get<LocalTransform>(left)->translation.z = 2.0f;
    registry.MarkChanged<LocalTransform>(left);
    system.Update(registry);
    EXPECT_EQ(system.Stats().lastRecomputed, 2u);  // left and leaf
    ExpectNear(WorldPosition(registry, leaf), vec3(-1.0f, 1.0f, 2.0f));
}

TEST(TransformSystemTest, ClearingOrChangingAParentMovesTheChild) {
    Registry registry;
    const Entity a = MakeNode(registry, vec3(10.0f, 0.0f, 0.0f));
    const Entity b = MakeNode(registry, vec3(0.0f, 20.0f, 0.0f));
    const Entity child = MakeNode(registry, vec3(0.0f, 0.0f, 1.0f));
    ASSERT_TRUE(SetParent(registry, child, a));
    TransformSystem system;
    system.Update(registry);
    ExpectNear(WorldPosition(registry, child), vec3(10.0f, 0.0f, 1.0f));

    ASSERT_TRUE(SetParent(registry, child, b));
    system.Update(registry);
    ExpectNear(WorldPosition(registry, child), vec3(0.0f, 20.0f, 1.0f));

    ASSERT_TRUE(ClearParent(registry, child));  // removal marks nothing: the system must notice
    system.Update(registry);
    ExpectNear(WorldPosition(registry, child), vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(system.Stats().lastRecomputed, 1u);
}

TEST(TransformSystemTest, WorldTransformsAddedDuringAPhaseAppearAtItsEnd) {
    Registry registry;
    const Entity e = MakeNode(registry, vec3(1.0f, 2.0f, 3.0f));
    TransformSystem system;
    registry.BeginDeferred();
    system.Update(registry);
    EXPECT_FALSE(registry.Has<WorldTransform>(e));
    registry.EndDeferred();
    ExpectNear(WorldPosition(registry, e), vec3(1.0f, 2.0f, 3.0f));
    EXPECT_EQ(registry.ChangedCount<WorldTransform>(), 1u);
}

// world = parent's world * local, by recursion: the same float operations in the same order.
glm::mat4 ExpectedWorld(const Registry& registry, Entity e) {
    const Parent* link = registry.Get<Parent>(e);
    const glm::mat4 parent = link ? ExpectedWorld(registry, link->entity) : glm::mat4(1.0f);
    return parent * ToMatrix(*registry.Get<LocalTransform>(e));
}

void Turn(Registry& registry, Entity e, float angle) {
    registry.Get<LocalTransform>(e)->rotation = glm::angleAxis(angle, vec3(0.0f, 0.0f, 1.0f));
    registry.MarkChanged<LocalTransform>(e);
}

// An animated crowd moves the same joints every frame: the system reuses its last order, and
// falls back to a full pass as soon as the set of moved entities is another one, also when a
// destroyed entity's index is taken by a new one.
TEST(TransformSystemTest, RepeatedMovesReuseTheOrderAndStayExact) {
    Registry registry;
    std::vector<Entity> joints;
    for (int tree = 0; tree < 40; ++tree) {
        Entity parent = MakeNode(registry, vec3(float(tree), 0.0f, 0.0f));
        for (int depth = 0; depth < 5; ++depth) {
            const Entity joint = MakeNode(registry, vec3(0.0f, 0.5f, 0.1f * float(depth)));
            ASSERT_TRUE(SetParent(registry, joint, parent));
            joints.push_back(joint);
            parent = joint;
        }
    }
    TransformSystem system;
    system.Update(registry);
    auto expectExact = [&] {
        registry.View<const WorldTransform>().Each([&](Entity e, const WorldTransform& w) {
            ASSERT_EQ(w.objectToWorld, ExpectedWorld(registry, e)) << "entity " << e.index;
        });
    };
    for (int frame = 1; frame <= 3; ++frame) {
        for (size_t j = 0; j < joints.size(); ++j)
            Turn(registry, joints[j], 0.1f * float(frame + j));
        system.Update(registry);
        expectExact();
        EXPECT_EQ(system.Stats().repeated, uint64_t(frame - 1));  // the first move is a full pass
        EXPECT_EQ(system.Stats().lastRecomputed, joints.size());
    }
    // One joint fewer moves, one root more: another set, a full pass.
    for (size_t j = 1; j < joints.size(); ++j) Turn(registry, joints[j], 0.7f);
    registry.Get<LocalTransform>(Entity{0, 0})->translation = vec3(0.0f, 3.0f, 0.0f);
    registry.MarkChanged<LocalTransform>(Entity{0, 0});
    system.Update(registry);
    expectExact();
    EXPECT_EQ(system.Stats().repeated, 2u);
    // A leaf joint destroyed and its index reused by a new root in the same frame; as many
    // entities move as before, but not the same ones.
    const Entity leaf = joints.back();
    joints.pop_back();
    ASSERT_TRUE(registry.Destroy(leaf));
    const Entity fresh = MakeNode(registry, vec3(7.0f, 7.0f, 7.0f));
    ASSERT_EQ(fresh.index, leaf.index);
    for (size_t j = 1; j < joints.size(); ++j) Turn(registry, joints[j], 0.9f);
    registry.MarkChanged<LocalTransform>(Entity{0, 0});
    system.Update(registry);
    expectExact();
    EXPECT_EQ(system.Stats().repeated, 2u);
}

}  // namespace
}  // namespace rtrt::physics
