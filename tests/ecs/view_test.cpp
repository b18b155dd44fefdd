// Views: intersections of pools, the smallest pool drives, missing pools, const access, and
// structural changes during iteration (deferred).
#include "engine/ecs/view.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <vector>

#include "engine/ecs/registry.h"

namespace rtrt::ecs {
namespace {

struct A {
    int value = 0;
};
struct B {
    int value = 0;
};
struct C {
    int value = 0;
};
struct Missing {
    int value = 0;
};

TEST(ViewTest, ViewOverATypeNeverAddedIsEmpty) {
    Registry registry;
    for (int i = 0; i < 5; ++i) registry.Add(registry.Create(), A{i});
    int visits = 0;
    registry.View<Missing>().Each([&](Entity, Missing&) { ++visits; });
    registry.View<A, Missing>().Each([&](Entity, A&, Missing&) { ++visits; });
    registry.View<Missing, const A>().Each([&](Entity, Missing&, const A&) { ++visits; });
    EXPECT_EQ(visits, 0);
}

TEST(ViewTest, ViewOverAnEmptiedPoolIsEmpty) {
    Registry registry;
    const Entity e = registry.Create();
    registry.Add(e, A{1});
    registry.Add(e, B{1});
    registry.Remove<B>(e);
    int visits = 0;
    registry.View<A, B>().Each([&](Entity, A&, B&) { ++visits; });
    EXPECT_EQ(visits, 0);
}

TEST(ViewTest, SingleComponentViewVisitsEveryOwnerWithItsValue) {
    Registry registry;
    std::map<uint32_t, int> expected;
    for (int i = 0; i < 10; ++i) {
        const Entity e = registry.Create();
        if (i % 3 == 0) continue;
        registry.Add(e, A{i * 7});
        expected[e.index] = i * 7;
    }
    std::map<uint32_t, int> seen;
    registry.View<A>().Each([&](Entity e, A& a) { seen[e.index] = a.value; });
    EXPECT_EQ(seen, expected);
}

// Pools of 100, 50 and 10 entities overlapping in 5. C is the smallest and was filled in reverse
// entity order, so the visiting order shows that C's dense list drove the loop.
TEST(ViewTest, ThreeComponentViewVisitsTheIntersectionInTheSmallestPoolsOrder) {
    Registry registry;
    std::vector<Entity> entities;
    for (int i = 0; i < 100; ++i) {
        entities.push_back(registry.Create());
        registry.Add(entities.back(), A{i});
        if (i % 2 == 0) registry.Add(entities.back(), B{i * 10});
    }
    for (int i = 90; i >= 81; --i) registry.Add(entities[i], C{i * 100});

    std::vector<int> order;
    registry.View<A, B, C>().Each([&](Entity e, A& a, B& b, C& c) {
        EXPECT_EQ(static_cast<int>(e.index), a.value);
        EXPECT_EQ(b.value, a.value * 10);
        EXPECT_EQ(c.value, a.value * 100);
        order.push_back(a.value);
    });
    EXPECT_EQ(order, (std::vector<int>{90, 88, 86, 84, 82}));

    // The same set whichever order the types are named in.
    std::vector<int> other;
    registry.View<C, A, B>().Each([&](Entity, C&, A& a, B&) { other.push_back(a.value); });
    EXPECT_EQ(other, order);
}

TEST(ViewTest, MutableViewWritesThroughAndConstViewReads) {
    Registry registry;
    for (int i = 0; i < 4; ++i) {
        const Entity e = registry.Create();
        registry.Add(e, A{i});
        registry.Add(e, B{100});
    }
    registry.View<A, const B>().Each([](Entity, A& a, const B& b) { a.value += b.value; });

    const Registry& constRegistry = registry;
    int sum = 0;
    constRegistry.View<const A>().Each([&](Entity, const A& a) { sum += a.value; });
    EXPECT_EQ(sum, 0 + 1 + 2 + 3 + 4 * 100);
}

TEST(ViewTest, DestroyingWhileIteratingUnderDeferralVisitsEverySurvivorOnce) {
    Registry registry;
    std::vector<Entity> entities;
    for (int i = 0; i < 50; ++i) {
        entities.push_back(registry.Create());
        registry.Add(entities.back(), A{i});
        registry.Add(entities.back(), B{i});
    }
    std::vector<int> visits(50, 0);
    {
        const ScopedDeferral deferral(registry);
        registry.View<A, B>().Each([&](Entity e, A& a, B&) {
            ++visits[a.value];
            // Destroy this entity and the one after it; the latter must still be visited.
            registry.Destroy(e);
            if (a.value + 1 < 50) registry.Destroy(entities[a.value + 1]);
        });
    }
    EXPECT_EQ(visits, std::vector<int>(50, 1));
    EXPECT_EQ(registry.AliveCount(), 0u);
    EXPECT_EQ(registry.Count<A>(), 0u);
    EXPECT_EQ(registry.Count<B>(), 0u);
}

TEST(ViewTest, AddAndRemoveDuringAViewAreDeferred) {
    Registry registry;
    std::vector<Entity> withBoth, onlyA;
    for (int i = 0; i < 10; ++i) {
        withBoth.push_back(registry.Create());
        registry.Add(withBoth.back(), A{i});
        registry.Add(withBoth.back(), B{i});
        onlyA.push_back(registry.Create());
        registry.Add(onlyA.back(), A{100 + i});
    }
    std::vector<int> seen;
    {
        const ScopedDeferral deferral(registry);
        registry.View<A, B>().Each([&](Entity e, A& a, B&) {
            seen.push_back(a.value);
            registry.Remove<B>(e);                   // still visited: the removal waits
            registry.Add(onlyA[a.value], B{0});      // not visited this pass
            registry.Add(registry.Create(), A{-1});  // neither is a new entity
            EXPECT_TRUE(registry.Has<B>(e));
        });
    }
    EXPECT_EQ(seen, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));

    std::vector<int> after;
    registry.View<A, B>().Each([&](Entity, A& a, B&) { after.push_back(a.value); });
    std::sort(after.begin(), after.end());
    EXPECT_EQ(after, (std::vector<int>{100, 101, 102, 103, 104, 105, 106, 107, 108, 109}));
    EXPECT_EQ(registry.Count<A>(), 30u);
    EXPECT_EQ(registry.AliveCount(), 30u);
}

}  // namespace
}  // namespace rtrt::ecs
