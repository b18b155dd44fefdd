// Entity handles: index reuse with a new generation, stale handles, retirement at the last
// generation, reservation for deferred creation.
#include "engine/ecs/entity.h"

#include <gtest/gtest.h>

#include <vector>

namespace rtrt::ecs {
namespace {

TEST(EntityTest, DefaultHandleIsNullAndNeverAlive) {
    EntityAllocator allocator;
    EXPECT_TRUE(Entity{}.IsNull());
    EXPECT_EQ(Entity{}, kNullEntity);
    allocator.Create();
    EXPECT_FALSE(allocator.IsAlive(kNullEntity));
    EXPECT_FALSE(allocator.Destroy(kNullEntity));
}

TEST(EntityTest, NewIndicesCountUpFromZeroAtGenerationZero) {
    EntityAllocator allocator;
    for (uint32_t i = 0; i < 3; ++i) {
        const Entity e = allocator.Create();
        EXPECT_EQ(e.index, i);
        EXPECT_EQ(e.generation, 0u);
        EXPECT_TRUE(allocator.IsAlive(e));
    }
    EXPECT_EQ(allocator.AliveCount(), 3u);
}

TEST(EntityTest, DestroyThenCreateReusesIndexWithNextGeneration) {
    EntityAllocator allocator;
    const Entity a = allocator.Create();
    const Entity b = allocator.Create();
    ASSERT_TRUE(allocator.Destroy(a));
    const Entity c = allocator.Create();
    EXPECT_EQ(c.index, a.index);
    EXPECT_EQ(c.generation, 1u);
    EXPECT_NE(c, a);
    EXPECT_FALSE(allocator.IsAlive(a));
    EXPECT_TRUE(allocator.IsAlive(b));
    EXPECT_TRUE(allocator.IsAlive(c));
    EXPECT_EQ(allocator.AliveCount(), 2u);
}

TEST(EntityTest, StaleHandleCannotDestroyTheIndexsNewOccupant) {
    EntityAllocator allocator;
    const Entity a = allocator.Create();
    allocator.Destroy(a);
    const Entity b = allocator.Create();
    EXPECT_FALSE(allocator.Destroy(a));
    EXPECT_TRUE(allocator.IsAlive(b));
    EXPECT_TRUE(allocator.Destroy(b));
    EXPECT_FALSE(allocator.Destroy(b));
    EXPECT_EQ(allocator.AliveCount(), 0u);
}

TEST(EntityTest, FreedIndicesAreReusedLastInFirstOut) {
    EntityAllocator allocator;
    const Entity e0 = allocator.Create();
    allocator.Create();
    const Entity e2 = allocator.Create();
    allocator.Destroy(e0);
    allocator.Destroy(e2);
    EXPECT_EQ(allocator.Create().index, 2u);
    EXPECT_EQ(allocator.Create().index, 0u);
    EXPECT_EQ(allocator.Create().index, 3u);
}

TEST(EntityTest, ForgedHandlesAreNotAlive) {
    EntityAllocator allocator;
    const Entity e = allocator.Create();
    EXPECT_FALSE(allocator.IsAlive(Entity{e.index, e.generation + 1}));
    EXPECT_FALSE(allocator.IsAlive(Entity{e.index + 1, 0}));
}

// The slot is retired at the last generation: its index is never issued again, so none of the
// handles it gave out can come back to life.
TEST(EntityTest, SlotAtMaxGenerationIsRetiredNotWrapped) {
    EntityAllocator allocator(/*maxGeneration=*/2);
    std::vector<Entity> issued;
    for (uint32_t generation = 0; generation <= 2; ++generation) {
        const Entity e = allocator.Create();
        EXPECT_EQ(e.index, 0u);
        EXPECT_EQ(e.generation, generation);
        issued.push_back(e);
        ASSERT_TRUE(allocator.Destroy(e));
    }
    const Entity next = allocator.Create();
    EXPECT_EQ(next.index, 1u);
    EXPECT_EQ(next.generation, 0u);
    for (const Entity e : issued) {
        EXPECT_FALSE(allocator.IsAlive(e));
        EXPECT_FALSE(allocator.Destroy(e));
    }
    EXPECT_EQ(allocator.AliveCount(), 1u);
}

TEST(EntityTest, DefaultPolicyKeeps32BitGenerations) {
    EXPECT_EQ(EntityAllocator::kMaxGeneration, 0xFFFFFFFFu);
}

TEST(EntityTest, ReservedEntityIsAliveOnlyAfterActivate) {
    EntityAllocator allocator;
    const Entity e = allocator.Reserve();
    EXPECT_TRUE(allocator.IsReserved(e));
    EXPECT_FALSE(allocator.IsAlive(e));
    EXPECT_FALSE(allocator.Destroy(e));
    EXPECT_EQ(allocator.AliveCount(), 0u);
    // The reserved index is taken: the next entity gets another.
    EXPECT_EQ(allocator.Create().index, e.index + 1);
    ASSERT_TRUE(allocator.Activate(e));
    EXPECT_TRUE(allocator.IsAlive(e));
    EXPECT_FALSE(allocator.IsReserved(e));
    EXPECT_FALSE(allocator.Activate(e));
    EXPECT_EQ(allocator.AliveCount(), 2u);
}

}  // namespace
}  // namespace rtrt::ecs
