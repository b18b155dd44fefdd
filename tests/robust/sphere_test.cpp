// Ray/sphere hard cases on the CPU: see sphere_checks.h for the cases and their expected values.
#include "tests/robust/cpu_runner.h"
#include "tests/robust/sphere_checks.h"

namespace rtrt::robust {
namespace {

TEST(SphereIntersect, SmallFarHugeAndInsideCasesMatchTheDoubleRoot) {
    CheckSphereCases(CpuRunner{});
}

}  // namespace
}  // namespace rtrt::robust
