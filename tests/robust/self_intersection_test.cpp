// Self-intersection on the CPU: spawned rays from far surfaces (spawn_checks.h).
#include "tests/robust/cpu_runner.h"
#include "tests/robust/spawn_checks.h"

namespace rtrt::robust {
namespace {

TEST(SelfIntersection, RaysSpawnedFromFarSurfacesLeaveThem) {
    CheckSpawnFromFarPlanes(CpuRunner{});
}

TEST(SelfIntersection, RaysContinuedIntoFarObjectsFindTheFarSide) {
    CheckSpawnIntoFarObjects(CpuRunner{});
}

}  // namespace
}  // namespace rtrt::robust
