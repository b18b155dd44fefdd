// ParallelFor visits every index of its range exactly once, whatever the grain; ParallelCompact
// keeps the serial filter's order on any number of threads.
#include "engine/core/parallel_for.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <memory>
#include <random>
#include <vector>

#include "engine/core/parallel_compact.h"

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

TEST(ParallelCompact, KeepsTheSerialOrderOnAnyThreadCount) {
    for (size_t n : {size_t(0), size_t(1), size_t(2047), size_t(2048), size_t(50001)}) {
        std::mt19937 rng{uint32_t(n)};
        std::vector<int> values(n);
        for (int& v : values) v = int(rng() % 3);
        std::vector<uint32_t> expected;
        for (size_t i = 0; i < n; ++i)
            if (values[i] == 0) expected.push_back(uint32_t(i));
        for (int threads : {1, 4}) {
            std::vector<uint32_t> got(n, ~0u), scratch;
            uint32_t kept = 0;
            tbb::task_arena(threads).execute([&] {
                kept = ParallelCompact(
                    n, scratch, [&](size_t i) { return values[i] == 0; },
                    [&](size_t i, uint32_t at) { got[at] = uint32_t(i); });
            });
            ASSERT_EQ(kept, expected.size()) << n;
            got.resize(kept);
            EXPECT_EQ(got, expected) << n << " values, " << threads << " threads";
        }
    }
}

}  // namespace
}  // namespace rtrt
