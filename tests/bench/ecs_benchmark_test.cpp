// The ECS benchmark measures what it says: its view visits every entity it created.
#include "bench/ecs_benchmark.h"

#include <gtest/gtest.h>

namespace rtrt::ecs {
namespace {

// x_i becomes i + 0.5 and the checksum sums 2 x_i: 1 + 3 + ... + (2n - 1) = n^2.
TEST(ViewTest, BenchmarkVisitsEveryEntity) {
    const EcsBenchResult result = RunEcsBenchmark(1000);
    EXPECT_EQ(result.checksum, 1000000u);
    EXPECT_GE(result.createMs, 0.0);
    EXPECT_GE(result.iterateMs, 0.0);
    EXPECT_GE(result.destroyMs, 0.0);
}

}  // namespace
}  // namespace rtrt::ecs
