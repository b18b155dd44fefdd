// Scheduler: fixed phase order, a flush after each phase, timings, bad registrations.
#include "engine/ecs/scheduler.h"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace rtrt::ecs {
namespace {

struct Health {
    int hp = 0;
};

TEST(SchedulerTest, PhasesRunInFixedOrderWhateverTheRegistrationOrder) {
    Scheduler scheduler;
    Registry registry;
    std::vector<std::string> log;
    auto logger = [&](std::string name) {
        return [&log, name](Registry&, float) { log.push_back(name); };
    };
    scheduler.AddSystem("extraction", "extract", logger("extract"));
    scheduler.AddSystem("animation", "animate", logger("animate"));
    scheduler.AddSystem("input", "keys", logger("keys"));
    scheduler.AddSystem("simulation", "physics", logger("physics"));
    scheduler.AddSystem("input", "mouse", logger("mouse"));
    scheduler.RunFrame(registry, 0.016f);
    scheduler.RunFrame(registry, 0.016f);
    const std::vector<std::string> frame{"keys", "mouse", "physics", "animate", "extract"};
    std::vector<std::string> twoFrames = frame;
    twoFrames.insert(twoFrames.end(), frame.begin(), frame.end());
    EXPECT_EQ(log, twoFrames);
}

TEST(SchedulerTest, SystemsGetTheFrameTimeStep) {
    Scheduler scheduler;
    Registry registry;
    float seen = 0.0f;
    scheduler.AddSystem("simulation", "step", [&](Registry&, float dt) { seen = dt; });
    scheduler.RunFrame(registry, 0.25f);
    EXPECT_EQ(seen, 0.25f);
}

// Changes made in a phase are invisible to the rest of that phase and visible to the next.
TEST(SchedulerTest, StructuralChangesFlushAtTheEndOfTheirPhase) {
    Scheduler scheduler;
    Registry registry;
    const Entity doomed = registry.Create();
    Entity spawned;
    std::vector<std::string> log;
    auto record = [&](const std::string& who, Registry& r) {
        log.push_back(who + (r.Valid(doomed) ? " doomed" : " -") +
                      (r.Valid(spawned) ? " spawned" : " -") + (r.Deferring() ? " deferred" : ""));
    };
    scheduler.AddSystem("input", "spawn", [&](Registry& r, float) {
        r.Destroy(doomed);
        spawned = r.Create();
        r.Add(spawned, Health{3});
        record("spawn", r);
    });
    scheduler.AddSystem("input", "after", [&](Registry& r, float) { record("after", r); });
    scheduler.AddSystem("simulation", "next", [&](Registry& r, float) { record("next", r); });
    scheduler.RunFrame(registry, 0.0f);

    EXPECT_EQ(log, (std::vector<std::string>{"spawn doomed - deferred", "after doomed - deferred",
                                             "next - spawned deferred"}));
    EXPECT_FALSE(registry.Deferring());
    ASSERT_TRUE(registry.Valid(spawned));
    EXPECT_EQ(registry.Get<Health>(spawned)->hp, 3);
}

TEST(SchedulerTest, SystemMayDestroyWhatItIteratesAndEverySurvivorIsVisitedOnce) {
    Scheduler scheduler;
    Registry registry;
    std::vector<Entity> entities;
    for (int i = 0; i < 100; ++i) {
        entities.push_back(registry.Create());
        registry.Add(entities.back(), Health{i});
    }
    std::vector<int> visits(100, 0);
    scheduler.AddSystem("simulation", "cull", [&](Registry& r, float) {
        r.View<Health>().Each([&](Entity e, Health& h) {
            ++visits[h.hp];
            if (h.hp % 2 == 0) r.Destroy(e);
        });
    });
    scheduler.AddSystem("animation", "count",
                        [&](Registry& r, float) { EXPECT_EQ(r.Count<Health>(), 50u); });
    scheduler.RunFrame(registry, 0.0f);
    EXPECT_EQ(visits, std::vector<int>(100, 1));
    EXPECT_EQ(registry.AliveCount(), 50u);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(registry.Valid(entities[i]), i % 2 == 1);
}

TEST(SchedulerTest, TimingsNameEverySystemInRunOrder) {
    Scheduler scheduler;
    Registry registry;
    scheduler.AddSystem("extraction", "slow", [](Registry&, float) {
        std::this_thread::sleep_for(std::chrono::milliseconds(3));
    });
    scheduler.AddSystem("input", "fast", [](Registry&, float) {});
    scheduler.RunFrame(registry, 0.0f);

    const auto systems = scheduler.SystemTimings();
    ASSERT_EQ(systems.size(), 2u);
    EXPECT_EQ(systems[0].phase, "input");
    EXPECT_EQ(systems[0].name, "fast");
    EXPECT_EQ(systems[1].phase, "extraction");
    EXPECT_EQ(systems[1].name, "slow");
    EXPECT_GE(systems[0].milliseconds, 0.0);
    EXPECT_GE(systems[1].milliseconds, 3.0);

    const auto phases = scheduler.PhaseTimings();
    ASSERT_EQ(phases.size(), 4u);
    EXPECT_EQ(phases[0].name, "input");
    EXPECT_EQ(phases[3].name, "extraction");
    EXPECT_GE(phases[3].milliseconds, systems[1].milliseconds);
}

TEST(SchedulerTest, CustomPhasesRunInTheGivenOrder) {
    const std::vector<std::string_view> phases{"late", "early"};
    Scheduler scheduler(phases);
    Registry registry;
    std::string log;
    scheduler.AddSystem("early", "e", [&](Registry&, float) { log += "e"; });
    scheduler.AddSystem("late", "l", [&](Registry&, float) { log += "l"; });
    scheduler.RunFrame(registry, 0.0f);
    EXPECT_EQ(log, "le");
}

TEST(SchedulerTest, RejectsUnknownPhasesTakenNamesAndRepeatedPhases) {
    Scheduler scheduler;
    EXPECT_THROW(scheduler.AddSystem("physics", "x", [](Registry&, float) {}),
                 std::invalid_argument);
    scheduler.AddSystem("input", "x", [](Registry&, float) {});
    EXPECT_THROW(scheduler.AddSystem("simulation", "x", [](Registry&, float) {}),
                 std::invalid_argument);
    const std::vector<std::string_view> repeated{"a", "b", "a"};
    EXPECT_THROW(Scheduler{repeated}, std::invalid_argument);
}

TEST(SchedulerTest, ThrowingSystemStillEndsThePhaseAndFlushes) {
    Scheduler scheduler;
    Registry registry;
    Entity e;
    scheduler.AddSystem("input", "fails", [&](Registry& r, float) {
        e = r.Create();
        throw std::runtime_error("system failed");
    });
    EXPECT_THROW(scheduler.RunFrame(registry, 0.0f), std::runtime_error);
    EXPECT_FALSE(registry.Deferring());
    EXPECT_TRUE(registry.Valid(e));
}

}  // namespace
}  // namespace rtrt::ecs
