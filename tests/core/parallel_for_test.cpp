// ParallelFor visits every index of its range exactly once, whatever the grain.
#include "engine/core/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <memory>

namespace rtrt {
namespace {

TEST(ParallelFor, EveryIndexOnce) {
    for (size_t grain : {1, 7, 4096}) {
        constexpr size_t kBegin = 3, kEnd = 10007;
        std::unique_ptr<std::atomic<int>[]> visits(new std::atomic<int>[kEnd]);
        for (size_t i = 0; i < kEnd; ++i) visits[i] = 0;
        ParallelFor(kBegin, kEnd, grain, [&](size_t i) { ++visits[i]; });
        for (size_t i = 0; i < kEnd; ++i) ASSERT_EQ(visits[i], i >= kBegin ? 1 : 0) << i;
    }
}

TEST(ParallelFor, EmptyRangeRunsNothing) {
    std::atomic<int> calls{0};
    ParallelFor(5, 5, 1, [&](size_t) { ++calls; });
    EXPECT_EQ(calls, 0);
}

}  // namespace
}  // namespace rtrt
