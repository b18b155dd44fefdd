// Ray/triangle primitive cases on the CPU: see triangle_checks.h for the expected values.
#include "tests/robust/cpu_runner.h"
#include "tests/robust/triangle_checks.h"

namespace rtrt::robust {
namespace {

TEST(TriangleIntersect, HitsDoNotDependOnTheDirectionsLength) {
    CheckTriangleDirectionScale(CpuRunner{});
}

TEST(TriangleIntersect, RetestingWithTMaxAtTheHitKeepsIt) {
    CheckTriangleTMaxIdempotent(CpuRunner{});
}

}  // namespace
}  // namespace rtrt::robust
