// The slab test's hard cases on the CPU (slab_checks.h), and the IsTraceable gate in front of it.
#include "tests/robust/cpu_runner.h"
#include "tests/robust/slab_checks.h"

namespace rtrt::robust {
namespace {

TEST(SlabTest, ZeroComponentsFacesFlatBoxesAndNanLanes) { CheckSlabCases(CpuRunner{}); }

// Expected: NaN or infinite components, a NaN tMax or a zero direction make a ray untraceable;
// large finite values do not (their sum would overflow, the gate must not compute it).
TEST(SlabTest, NanAndInfiniteRaysAreNotTraceable) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(IsTraceable(Ray{vec3(0), kInfinity, vec3(nan, 0, 1), 0}));
    EXPECT_FALSE(IsTraceable(Ray{vec3(kInfinity, 0, 0), kInfinity, vec3(0, 0, 1), 0}));
    EXPECT_FALSE(IsTraceable(Ray{vec3(0), kInfinity, vec3(0), 0}));
    EXPECT_FALSE(IsTraceable(Ray{vec3(0), kInfinity, vec3(-0.0f), 0}));
    EXPECT_FALSE(IsTraceable(Ray{vec3(0), nan, vec3(0, 0, 1), 0}));
    EXPECT_TRUE(IsTraceable(Ray{vec3(0), kInfinity, vec3(0, 0, 1), 0}));
    EXPECT_TRUE(IsTraceable(Ray{vec3(3e38f), kInfinity, vec3(3e38f, 3e38f, 1), 0}));
}

}  // namespace
}  // namespace rtrt::robust
