// The animation system: poses only entities with an Animator, marks them changed, combines a
// clip with procedural motions; and the module's systems in the scheduler.
#include "engine/physics_anim/animator.h"

#include <gtest/gtest.h>

#include <memory>

#include "engine/physics_anim/physics_anim_systems.h"

namespace rtrt::physics {
namespace {

using ecs::Entity;
using ecs::Registry;

void ExpectNear(vec3 actual, vec3 expected, float tolerance = 1e-5f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

std::shared_ptr<const KeyframeClip> SlideClip() {
    auto clip = std::make_shared<KeyframeClip>();
    clip->translation.times = {0.0f, 2.0f};
    clip->translation.values = {vec3(0.0f), vec3(4.0f, 0.0f, 0.0f)};
    clip->wrap = WrapMode::kLoop;
    return clip;
}

TEST(AnimatorTest, OnlyEntitiesWithAnimatorsArePosedAndMarked) {
    Registry registry;
    const Entity animated = registry.Create();
    registry.Add(animated, LocalTransform{});
    Animator animator;
    animator.clip = SlideClip();
    registry.Add(animated, animator);
    const Entity bystander = registry.Create();
    registry.Add(bystander, LocalTransform{vec3(9.0f)});
    registry.ClearChanged<LocalTransform>();

    EXPECT_EQ(AnimateEntities(registry, 0.5f), 1u);
    ExpectNear(registry.Get<LocalTransform>(animated)->translation, vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(registry.Get<LocalTransform>(bystander)->translation, vec3(9.0f));
    ASSERT_EQ(registry.ChangedCount<LocalTransform>(), 1u);
    registry.EachChanged<LocalTransform>(
        [&](Entity e, LocalTransform&) { EXPECT_EQ(e, animated); });
}

TEST(AnimatorTest, SpeedScalesTimeAndPausedAnimatorsAreLeftAlone) {
    Registry registry;
    const Entity fast = registry.Create();
    registry.Add(fast, LocalTransform{});
    Animator animator;
    animator.clip = SlideClip();
    animator.speed = 2.0f;
    registry.Add(fast, animator);
    const Entity paused = registry.Create();
    registry.Add(paused, LocalTransform{vec3(7.0f)});
    animator.playing = false;
    registry.Add(paused, animator);
    registry.ClearChanged<LocalTransform>();

    EXPECT_EQ(AnimateEntities(registry, 0.25f), 1u);
    ExpectNear(registry.Get<LocalTransform>(fast)->translation, vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(registry.Get<LocalTransform>(paused)->translation, vec3(7.0f));
    EXPECT_EQ(registry.Get<Animator>(paused)->time, 0.0);
}

TEST(AnimatorTest, ClipThenMotionsInOrder) {
    Animator animator;
    animator.clip = SlideClip();  // translation only
    animator.motions.push_back(Spin{vec3(0.0f, 1.0f, 0.0f), kPi});
    animator.motions.push_back(Bob{0.5f, 0.25f, vec3(0.0f, 1.0f, 0.0f)});
    animator.time = 1.0;
    const LocalTransform pose = EvaluateAnimator(animator);
    // Clip: x = 2; bob: a quarter cycle at 0.25 Hz lifts by the amplitude; spin: half a turn.
    ExpectNear(pose.translation, vec3(2.0f, 0.5f, 0.0f));
    ExpectNear(pose.rotation * vec3(1.0f, 0.0f, 0.0f), vec3(-1.0f, 0.0f, 0.0f));
}

// A clip that has ended and a spin of speed 0 pose their entities where they were: nothing is
// marked changed, so nothing is handed on to extraction (they had been marked every frame).
TEST(AnimatorTest, APoseThatDoesNotChangeIsNotMarked) {
    Registry registry;
    const Entity ended = registry.Create();
    registry.Add(ended, LocalTransform{});
    Animator once;
    auto clip = std::make_shared<KeyframeClip>(*SlideClip());
    clip->wrap = WrapMode::kClamp;
    once.clip = clip;
    registry.Add(ended, once);
    const Entity still = registry.Create();
    registry.Add(still, LocalTransform{});
    Animator spin;
    spin.motions.push_back(Spin{vec3(0.0f, 1.0f, 0.0f), 0.0f});
    registry.Add(still, spin);
    AnimateEntities(registry, 3.0f);                         // past the clip's end
    EXPECT_EQ(registry.ChangedCount<LocalTransform>(), 2u);  // added, then moved
    registry.ClearChanged<LocalTransform>();
    EXPECT_EQ(AnimateEntities(registry, 1.0f / 60.0f), 2u);
    EXPECT_EQ(registry.ChangedCount<LocalTransform>(), 0u);
    ExpectNear(registry.Get<LocalTransform>(ended)->translation, vec3(4.0f, 0.0f, 0.0f));
}

// A user's move and turn of an animated entity (the window's drag, World::SetPose) lasts: the
// animation plays on from there instead of putting it back.
TEST(AnimatorTest, APlacedAnimatorPlaysOnFromWhereItWasPut) {
    Animator animator;
    animator.clip = SlideClip();
    animator.motions.push_back(Spin{vec3(0.0f, 1.0f, 0.0f), kPi});
    animator.time = 0.5;  // x = 1, a quarter turn
    const glm::quat turn = glm::angleAxis(kPi / 2.0f, vec3(0.0f, 0.0f, 1.0f));
    const LocalTransform before = EvaluateAnimator(animator);
    PlaceAnimated(animator, vec3(1.0f, 3.0f, -2.0f), turn * before.rotation);
    const LocalTransform placed = EvaluateAnimator(animator);
    ExpectNear(placed.translation, vec3(1.0f, 3.0f, -2.0f));
    ExpectNear(placed.rotation * vec3(1.0f, 0.0f, 0.0f),
               turn * (before.rotation * vec3(1.0f, 0.0f, 0.0f)));
    animator.time = 1.0;  // the slide goes on by 1 along x, the spin by another quarter turn
    const LocalTransform later = EvaluateAnimator(animator);
    ExpectNear(later.translation, vec3(2.0f, 3.0f, -2.0f));
    const glm::quat quarter = glm::angleAxis(kPi / 2.0f, vec3(0.0f, 1.0f, 0.0f));
    ExpectNear(later.rotation * vec3(1.0f, 0.0f, 0.0f),
               turn * (before.rotation * (quarter * vec3(1.0f, 0.0f, 0.0f))));
}

// The scheduler runs animators and then the transform system in "animation", so a child of an
// animated parent has its world transform by extraction.
TEST(AnimatorTest, AnimatedParentMovesItsChildWithinTheFrame) {
    Registry registry;
    ecs::Scheduler scheduler;
    PhysicsWorld physics;
    TransformSystem transforms;
    AddPhysicsAnimSystems(scheduler, physics, transforms);
    vec3 seenByExtraction(-1.0f);
    const Entity parent = registry.Create();
    registry.Add(parent, LocalTransform{});
    Animator animator;
    animator.motions.push_back(Orbit{vec3(0.0f), 1.0f, vec3(0.0f, 1.0f, 0.0f), 4.0f});
    registry.Add(parent, animator);
    const Entity child = registry.Create();
    registry.Add(child, LocalTransform{vec3(0.0f, 1.0f, 0.0f)});
    ASSERT_TRUE(SetParent(registry, child, parent));
    scheduler.AddSystem("extraction", "probe", [&](Registry& r, float) {
        seenByExtraction = vec3(r.Get<WorldTransform>(child)->objectToWorld[3]);
    });
    scheduler.RunFrame(registry, 1.0f);  // a quarter of the orbit: the parent is at -Z
    ExpectNear(seenByExtraction, vec3(0.0f, 1.0f, -1.0f));
    EXPECT_EQ(physics.Stats().frames, 0u);  // no rigid bodies: the physics system did nothing
}

}  // namespace
}  // namespace rtrt::physics
