// Watertightness on the CPU: see watertight_checks.h for the cases and their expected values.
#include "tests/robust/cpu_runner.h"
#include "tests/robust/watertight_checks.h"

namespace rtrt::robust {
namespace {

TEST(Watertight, RaysAtSharedVerticesAndEdgesOfClosedMeshesNeverPassThrough) {
    CheckWatertightAll(CpuRunner{});
}

}  // namespace
}  // namespace rtrt::robust
