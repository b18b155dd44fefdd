#pragma once
// Times the registry's bulk operations: create, iterate a view, destroy.
#include <cstdint>

namespace rtrt::ecs {

struct EcsBenchResult {
    double createMs, iterateMs, destroyMs;  // median of three runs
    uint64_t checksum;                      // entityCount^2 when the view visited everything
};

// Creates entityCount entities with a Position and a Velocity (every fourth also a Mass), runs one
// pass of a Position+Velocity view that moves them, and destroys them all; three runs on a fresh
// registry each.
EcsBenchResult RunEcsBenchmark(uint32_t entityCount);

}  // namespace rtrt::ecs
