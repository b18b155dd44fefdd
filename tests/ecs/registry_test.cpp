// Registry: components on entities, stale handles, swap-and-pop removal, deferral, change tracking.
#include "engine/ecs/registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <vector>

namespace rtrt::ecs {
namespace {

struct Position {
    float x = 0.0f, y = 0.0f;
};
struct Health {
    int hp = 0;
};
struct NeverAdded {
    int unused = 0;
};

TEST(RegistryTest, AddGetHasRemove) {
    Registry registry;
    const Entity e = registry.Create();
    EXPECT_TRUE(registry.Valid(e));
    EXPECT_FALSE(registry.Has<Position>(e));
    EXPECT_EQ(registry.Get<Position>(e), nullptr);

    ASSERT_TRUE(registry.Add(e, Position{1.5f, -2.0f}));
    ASSERT_TRUE(registry.Has<Position>(e));
    EXPECT_EQ(registry.Get<Position>(e)->x, 1.5f);
    EXPECT_EQ(registry.Get<Position>(e)->y, -2.0f);
    EXPECT_FALSE(registry.Has<Health>(e));

    EXPECT_TRUE(registry.Remove<Position>(e));
    EXPECT_FALSE(registry.Has<Position>(e));
    EXPECT_FALSE(registry.Remove<Position>(e));
    EXPECT_EQ(registry.Count<Position>(), 0u);
}

TEST(RegistryTest, AddWithoutValueValueInitialises) {
    Registry registry;
    const Entity e = registry.Create();
    ASSERT_TRUE(registry.Add<Health>(e));
    EXPECT_EQ(registry.Get<Health>(e)->hp, 0);
}

TEST(RegistryTest, AddReplacesAnExistingComponent) {
    Registry registry;
    const Entity e = registry.Create();
    registry.Add(e, Health{10});
    registry.Add(e, Health{25});
    EXPECT_EQ(registry.Get<Health>(e)->hp, 25);
    EXPECT_EQ(registry.Count<Health>(), 1u);
}

TEST(RegistryTest, ComponentTypeNeverAddedIsAbsentNotAnError) {
    Registry registry;
    const Entity e = registry.Create();
    EXPECT_FALSE(registry.Has<NeverAdded>(e));
    EXPECT_EQ(registry.Get<NeverAdded>(e), nullptr);
    EXPECT_FALSE(registry.Remove<NeverAdded>(e));
    EXPECT_EQ(registry.Count<NeverAdded>(), 0u);
    const Registry& constRegistry = registry;
    EXPECT_EQ(constRegistry.Get<NeverAdded>(e), nullptr);
}

TEST(RegistryTest, StaleHandleIsDetectedByEveryCallAndNeverAliasesTheNewEntity) {
    Registry registry;
    const Entity old = registry.Create();
    registry.Add(old, Health{7});
    ASSERT_TRUE(registry.Destroy(old));

    const Entity reused = registry.Create();
    ASSERT_EQ(reused.index, old.index);
    ASSERT_EQ(reused.generation, old.generation + 1);
    EXPECT_FALSE(registry.Has<Health>(reused));  // the old entity's components went with it
    registry.Add(reused, Health{99});

    EXPECT_FALSE(registry.Valid(old));
    EXPECT_FALSE(registry.Has<Health>(old));
    EXPECT_EQ(registry.Get<Health>(old), nullptr);
    EXPECT_FALSE(registry.Add(old, Health{1}));
    EXPECT_FALSE(registry.Remove<Health>(old));
    EXPECT_FALSE(registry.Destroy(old));

    EXPECT_TRUE(registry.Valid(reused));
    ASSERT_NE(registry.Get<Health>(reused), nullptr);
    EXPECT_EQ(registry.Get<Health>(reused)->hp, 99);
    EXPECT_EQ(registry.AliveCount(), 1u);
}

TEST(RegistryTest, DestroyRemovesEveryComponent) {
    Registry registry;
    const Entity a = registry.Create();
    const Entity b = registry.Create();
    registry.Add(a, Position{});
    registry.Add(a, Health{1});
    registry.Add(b, Health{2});
    registry.Destroy(a);
    EXPECT_EQ(registry.Count<Position>(), 0u);
    EXPECT_EQ(registry.Count<Health>(), 1u);
    EXPECT_EQ(registry.Get<Health>(b)->hp, 2);
    EXPECT_EQ(registry.AliveCount(), 1u);
}

TEST(RegistryTest, SwapAndPopRemovalKeepsEveryOtherComponent) {
    Registry registry;
    std::vector<Entity> entities;
    for (int i = 0; i < 6; ++i) {
        entities.push_back(registry.Create());
        registry.Add(entities.back(), Health{i * 10});
    }
    registry.Remove<Health>(entities[1]);  // the last (50) moves into its place
    registry.Remove<Health>(entities[5]);  // now at position 1
    registry.Remove<Health>(entities[4]);  // the last one
    EXPECT_EQ(registry.Count<Health>(), 3u);
    EXPECT_EQ(registry.Get<Health>(entities[0])->hp, 0);
    EXPECT_EQ(registry.Get<Health>(entities[2])->hp, 20);
    EXPECT_EQ(registry.Get<Health>(entities[3])->hp, 30);
    for (const int removed : {1, 4, 5}) {
        EXPECT_EQ(registry.Get<Health>(entities[removed]), nullptr);
    }
}

// Indices across several 4096-entry pages of the sparse index, and a pool that only holds the
// highest ones.
TEST(RegistryTest, ManyEntitiesAcrossSparsePages) {
    Registry registry;
    constexpr int kCount = 10000;
    std::vector<Entity> entities;
    for (int i = 0; i < kCount; ++i) {
        entities.push_back(registry.Create());
        registry.Add(entities.back(), Health{i});
        if (i >= 9000) registry.Add(entities.back(), Position{static_cast<float>(i), 0.0f});
    }
    for (int i = 0; i < kCount; i += 2) registry.Destroy(entities[i]);
    EXPECT_EQ(registry.AliveCount(), 5000u);
    EXPECT_EQ(registry.Count<Health>(), 5000u);
    EXPECT_EQ(registry.Count<Position>(), 500u);
    for (int i = 0; i < kCount; ++i) {
        const Health* health = registry.Get<Health>(entities[i]);
        if (i % 2 == 0) {
            EXPECT_EQ(health, nullptr);
        } else {
            ASSERT_NE(health, nullptr);
            EXPECT_EQ(health->hp, i);
            EXPECT_EQ(registry.Has<Position>(entities[i]), i >= 9000);
        }
    }
}

TEST(RegistryTest, DeferredCreateIsValidOnlyAfterTheFlush) {
    Registry registry;
    Entity e;
    {
        const ScopedDeferral deferral(registry);
        e = registry.Create();
        EXPECT_FALSE(e.IsNull());
        EXPECT_FALSE(registry.Valid(e));
        EXPECT_TRUE(registry.Add(e, Health{3}));
        EXPECT_FALSE(registry.Has<Health>(e));
        EXPECT_EQ(registry.AliveCount(), 0u);
    }
    EXPECT_TRUE(registry.Valid(e));
    ASSERT_NE(registry.Get<Health>(e), nullptr);
    EXPECT_EQ(registry.Get<Health>(e)->hp, 3);
    EXPECT_EQ(registry.AliveCount(), 1u);
}

TEST(RegistryTest, DeferredDestroyKeepsTheEntityUntilTheFlush) {
    Registry registry;
    const Entity e = registry.Create();
    registry.Add(e, Health{4});
    registry.BeginDeferred();
    EXPECT_TRUE(registry.Destroy(e));
    EXPECT_TRUE(registry.Destroy(e));  // still alive, so recorded again; the flush ignores it
    EXPECT_TRUE(registry.Valid(e));
    EXPECT_EQ(registry.Get<Health>(e)->hp, 4);
    registry.EndDeferred();
    EXPECT_FALSE(registry.Valid(e));
    EXPECT_EQ(registry.Count<Health>(), 0u);
    EXPECT_EQ(registry.AliveCount(), 0u);
}

TEST(RegistryTest, DeferredCommandsApplyInRecordedOrder) {
    Registry registry;
    const Entity addThenRemove = registry.Create();
    const Entity removeThenAdd = registry.Create();
    const Entity destroyThenAdd = registry.Create();
    registry.Add(removeThenAdd, Health{1});
    {
        const ScopedDeferral deferral(registry);
        registry.Add(addThenRemove, Health{2});
        registry.Remove<Health>(addThenRemove);
        registry.Remove<Health>(removeThenAdd);
        registry.Add(removeThenAdd, Health{5});
        registry.Destroy(destroyThenAdd);
        registry.Add(destroyThenAdd, Health{6});  // dropped: the entity is gone by then
        const Entity createdAndDestroyed = registry.Create();
        registry.Add(createdAndDestroyed, Health{7});
        registry.Destroy(createdAndDestroyed);
        EXPECT_EQ(registry.Get<Health>(removeThenAdd)->hp, 1);
    }
    EXPECT_FALSE(registry.Has<Health>(addThenRemove));
    ASSERT_TRUE(registry.Has<Health>(removeThenAdd));
    EXPECT_EQ(registry.Get<Health>(removeThenAdd)->hp, 5);
    EXPECT_FALSE(registry.Valid(destroyThenAdd));
    EXPECT_EQ(registry.Count<Health>(), 1u);
    EXPECT_EQ(registry.AliveCount(), 2u);
}

TEST(RegistryTest, DeferredCallsOnStaleHandlesFailAtOnce) {
    Registry registry;
    const Entity e = registry.Create();
    registry.Add(e, Health{1});
    registry.Destroy(e);
    const ScopedDeferral deferral(registry);
    EXPECT_FALSE(registry.Destroy(e));
    EXPECT_FALSE(registry.Add(e, Health{2}));
    EXPECT_FALSE(registry.Remove<Health>(e));
}

TEST(RegistryTest, NestedDeferralFlushesAtTheOutermostEnd) {
    Registry registry;
    registry.BeginDeferred();
    registry.BeginDeferred();
    const Entity e = registry.Create();
    registry.EndDeferred();
    EXPECT_TRUE(registry.Deferring());
    EXPECT_FALSE(registry.Valid(e));
    registry.EndDeferred();
    EXPECT_FALSE(registry.Deferring());
    EXPECT_TRUE(registry.Valid(e));
}

std::vector<int> ChangedHealth(Registry& registry) {
    std::vector<int> hp;
    registry.EachChanged<Health>([&](Entity, Health& h) { hp.push_back(h.hp); });
    return hp;
}

TEST(RegistryTest, ChangeTrackingListsMarkedEntitiesOnceUntilCleared) {
    Registry registry;
    std::vector<Entity> entities;
    for (int i = 0; i < 4; ++i) {
        entities.push_back(registry.Create());
        registry.Add(entities.back(), Health{i});
    }
    // Adding marks.
    EXPECT_EQ(ChangedHealth(registry), (std::vector<int>{0, 1, 2, 3}));
    registry.ClearChanged<Health>();
    EXPECT_EQ(registry.ChangedCount<Health>(), 0u);
    EXPECT_TRUE(ChangedHealth(registry).empty());

    registry.MarkChanged<Health>(entities[2]);
    registry.MarkChanged<Health>(entities[0]);
    registry.MarkChanged<Health>(entities[2]);
    EXPECT_EQ(ChangedHealth(registry), (std::vector<int>{2, 0}));

    // Replacing marks; a mark on an entity without the component, or a stale one, is ignored.
    registry.Add(entities[3], Health{30});
    const Entity bare = registry.Create();
    registry.MarkChanged<Health>(bare);
    registry.MarkChanged<NeverAdded>(bare);
    EXPECT_EQ(ChangedHealth(registry), (std::vector<int>{2, 0, 30}));

    // Losing the component, or the entity, unmarks.
    registry.Remove<Health>(entities[0]);
    registry.Destroy(entities[2]);
    registry.MarkChanged<Health>(entities[2]);
    EXPECT_EQ(ChangedHealth(registry), (std::vector<int>{30}));
    EXPECT_EQ(registry.ChangedCount<Health>(), 1u);
}

// The bulk MarkChanged (checked in parallel) lists what marking one after another lists, in the
// same order: over several sparse pages and compaction chunks, with entities already marked, ones
// without the component and stale handles.
TEST(RegistryTest, BulkMarkingListsWhatMarkingOneByOneLists) {
    constexpr int kEntities = 9000;
    Registry one;
    Registry bulk;
    std::vector<Entity> entities;
    for (int i = 0; i < kEntities; ++i) {
        const Entity e = one.Create();
        ASSERT_EQ(bulk.Create(), e);
        entities.push_back(e);
        if (i % 5 != 0) {  // every fifth has no Health
            one.Add(e, Health{i});
            bulk.Add(e, Health{i});
        }
    }
    for (Registry* registry : {&one, &bulk}) {
        registry->ClearChanged<Health>();
        for (int i = 0; i < kEntities; i += 7) registry->MarkChanged<Health>(entities[i]);
        registry->Destroy(entities[kEntities - 3]);  // a stale handle
    }
    std::vector<Entity> marks;
    for (int i = kEntities - 1; i >= 0; i -= 2) marks.push_back(entities[i]);  // backwards
    for (const Entity e : marks) one.MarkChanged<Health>(e);
    bulk.MarkChanged<Health>(std::span<const Entity>(marks));
    std::vector<Entity> listedOne;
    std::vector<Entity> listedBulk;
    one.EachChanged<Health>([&](Entity e, Health&) { listedOne.push_back(e); });
    bulk.EachChanged<Health>([&](Entity e, Health&) { listedBulk.push_back(e); });
    EXPECT_GT(listedOne.size(), 4000u);
    EXPECT_EQ(listedBulk, listedOne);
    // And the marks behave as ever afterwards: found, cleared, removed.
    EXPECT_TRUE(bulk.IsChanged<Health>(entities[kEntities - 1]));
    EXPECT_FALSE(bulk.IsChanged<Health>(entities[kEntities - 3]));
    bulk.Remove<Health>(entities[1]);
    EXPECT_FALSE(bulk.IsChanged<Health>(entities[1]));
    EXPECT_EQ(bulk.ChangedCount<Health>(), listedOne.size() - 1);
    bulk.ClearChanged<Health>();
    EXPECT_EQ(bulk.ChangedCount<Health>(), 0u);
    bulk.MarkChanged<Health>(std::span<const Entity>(marks));
    const auto withHealth =
        std::count_if(marks.begin(), marks.end(), [&](Entity e) { return bulk.Has<Health>(e); });
    EXPECT_EQ(bulk.ChangedCount<Health>(), static_cast<size_t>(withHealth));
}

TEST(RegistryTest, EachChangedGivesMutableComponentsAndConstAccess) {
    Registry registry;
    const Entity e = registry.Create();
    registry.Add(e, Health{1});
    registry.EachChanged<Health>([](Entity, Health& h) { h.hp = 8; });
    const Registry& constRegistry = registry;
    int seen = 0;
    constRegistry.EachChanged<Health>([&](Entity visited, const Health& h) {
        EXPECT_EQ(visited, e);
        seen = h.hp;
    });
    EXPECT_EQ(seen, 8);
}

TEST(RegistryTest, MarksMadeDuringEachChangedWaitForTheNextPass) {
    Registry registry;
    std::vector<Entity> entities;
    for (int i = 0; i < 3; ++i) {
        entities.push_back(registry.Create());
        registry.Add(entities.back(), Health{i});
    }
    registry.ClearChanged<Health>();
    registry.MarkChanged<Health>(entities[0]);
    int visits = 0;
    registry.EachChanged<Health>([&](Entity, Health&) {
        ++visits;
        registry.MarkChanged<Health>(entities[1]);
        registry.MarkChanged<Health>(entities[2]);
    });
    EXPECT_EQ(visits, 1);
    EXPECT_EQ(registry.ChangedCount<Health>(), 3u);
}

// Removing a T, destroying an entity or clearing the marks from inside EachChanged: the walk
// had read past the end of the changed list it shrank (and skipped the entry moved into place).
TEST(RegistryTest, StructuralChangesDuringEachChangedWaitUntilItEnds) {
    Registry registry;
    std::vector<Entity> entities;
    for (int i = 0; i < 4; ++i) {
        entities.push_back(registry.Create());
        registry.Add(entities.back(), Health{i});
    }
    std::vector<int> visited;
    registry.EachChanged<Health>([&](Entity e, Health& h) {
        visited.push_back(h.hp);
        if (e != entities[0]) return;
        EXPECT_TRUE(registry.Remove<Health>(entities[1]));
        EXPECT_TRUE(registry.Destroy(entities[2]));
        EXPECT_TRUE(registry.Remove<Health>(entities[0]));
    });
    EXPECT_EQ(visited, (std::vector<int>{0, 1, 2, 3}));
    EXPECT_FALSE(registry.Has<Health>(entities[0]));
    EXPECT_FALSE(registry.Has<Health>(entities[1]));
    EXPECT_FALSE(registry.Valid(entities[2]));
    EXPECT_EQ(ChangedHealth(registry), (std::vector<int>{3}));

    int visits = 0;
    registry.MarkChanged<Health>(entities[3]);
    registry.Add(entities[0], Health{7});
    registry.EachChanged<Health>([&](Entity, Health&) {
        ++visits;
        registry.ClearChanged<Health>();
        registry.MarkChanged<Health>(entities[3]);  // for the next pass, as any mark made here
        registry.MarkChanged<Health>(entities[0]);
    });
    EXPECT_EQ(visits, 1);
    EXPECT_EQ(registry.ChangedCount<Health>(), 2u);
}

TEST(RegistryTest, AMovedFromRegistryIsEmpty) {
    Registry from;
    const Entity a = from.Create();
    from.Add(a, Health{1});
    from.BeginDeferred();
    Registry to = std::move(from);
    EXPECT_EQ(from.AliveCount(), 0u);
    EXPECT_FALSE(from.Deferring());
    const Entity fresh = from.Create();
    EXPECT_TRUE(from.Valid(fresh));
    EXPECT_EQ(from.AliveCount(), 1u);
    EXPECT_FALSE(from.Has<Health>(fresh));
    EXPECT_TRUE(to.Deferring());
    to.EndDeferred();
    EXPECT_TRUE(to.Valid(a));
    EXPECT_EQ(to.Get<Health>(a)->hp, 1);
    EXPECT_EQ(to.AliveCount(), 1u);
}

TEST(RegistryTest, DeferredAddMarksChangedAtTheFlush) {
    Registry registry;
    const Entity e = registry.Create();
    {
        const ScopedDeferral deferral(registry);
        registry.Add(e, Health{5});
        EXPECT_EQ(registry.ChangedCount<Health>(), 0u);
    }
    EXPECT_EQ(ChangedHealth(registry), (std::vector<int>{5}));
}

}  // namespace
}  // namespace rtrt::ecs
