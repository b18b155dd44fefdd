#include "bench/ecs_benchmark.h"

#include <vector>

#include "engine/core/timer.h"
#include "engine/ecs/registry.h"

namespace rtrt::ecs {
namespace {

struct Position {
    float x, y, z;
};
struct Velocity {
    float x, y, z;
};
struct Mass {
    float kg;
};

constexpr int kRuns = 3;
constexpr float kDt = 0.5f;

struct RunTimes {
    double createMs, iterateMs, destroyMs;
    uint64_t checksum;
};

RunTimes RunOnce(uint32_t entityCount) {
    Registry registry;
    std::vector<Entity> entities(entityCount);
    RunTimes times{};

    Stopwatch clock;
    for (uint32_t i = 0; i < entityCount; ++i) {
        const Entity e = registry.Create();
        registry.Add(e, Position{static_cast<float>(i), 0.0f, 0.0f});
        registry.Add(e, Velocity{1.0f, 2.0f, 3.0f});
        if (i % 4 == 0) registry.Add(e, Mass{1.0f});
        entities[i] = e;
    }
    times.createMs = clock.Milliseconds();

    // x becomes i + 0.5, exact in float below 2^23 entities, so 2x sums to entityCount^2.
    clock.Restart();
    uint64_t checksum = 0;
    registry.View<Position, const Velocity>().Each([&](Entity, Position& p, const Velocity& v) {
        p.x += v.x * kDt;
        p.y += v.y * kDt;
        p.z += v.z * kDt;
        checksum += static_cast<uint64_t>(2.0f * p.x);
    });
    times.iterateMs = clock.Milliseconds();
    times.checksum = checksum;

    clock.Restart();
    for (const Entity e : entities) registry.Destroy(e);
    times.destroyMs = clock.Milliseconds();
    return times;
}

}  // namespace

EcsBenchResult RunEcsBenchmark(uint32_t entityCount) {
    std::vector<double> create, iterate, destroy;
    uint64_t checksum = 0;
    for (int run = 0; run < kRuns; ++run) {
        const RunTimes times = RunOnce(entityCount);
        create.push_back(times.createMs);
        iterate.push_back(times.iterateMs);
        destroy.push_back(times.destroyMs);
        checksum = times.checksum;
    }
    return {Median(create), Median(iterate), Median(destroy), checksum};
}

}  // namespace rtrt::ecs
