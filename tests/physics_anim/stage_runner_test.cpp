// StageRunner: every block of every share runs exactly once; a block starts only after the
// blocks it waits for have finished (all of the stage before without dependencies; the shares
// named in waitFor and all of the stages before the one before with them); a run completes whether
// or not TBB lends the threads asked for.
#include "engine/physics_anim/stage_runner.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <random>
#include <thread>
#include <vector>

namespace rtrt::physics {
namespace {

constexpr size_t kStages = 40;
constexpr uint32_t kMaxBlocks = 4;

struct Times {
    uint64_t start = 0;
    uint64_t end = 0;
    int runs = 0;
};

void RunAndCheck(int threads, bool withDependencies) {
    const auto shares = static_cast<size_t>(std::max(threads, 1));
    std::mt19937 random(static_cast<uint32_t>(threads * 2 + withDependencies));
    std::vector<uint32_t> blocks(kStages * shares);
    for (uint32_t& b : blocks) b = random() % (kMaxBlocks + 1);  // 0 to 4
    std::vector<uint64_t> waitFor;
    if (withDependencies) {
        waitFor.resize(kStages * shares);
        for (size_t t = 0; t < kStages; ++t) {
            for (size_t s = 0; s < shares; ++s) {
                // The share itself and a random one of the stage before.
                waitFor[t * shares + s] = (uint64_t{1} << s) | (uint64_t{1} << (random() % shares));
            }
        }
    }
    std::vector<Times> times(kStages * shares * kMaxBlocks);
    std::atomic<uint64_t> clock{1};  // 0: the end of a share without blocks
    StageRunner runner;
    runner.Run(blocks, waitFor, threads, [&](size_t stage, uint32_t share, uint32_t block) {
        ASSERT_LT(share, shares);
        ASSERT_LT(block, blocks[stage * shares + share]);
        Times& t = times[(stage * shares + share) * kMaxBlocks + block];
        t.start = clock.fetch_add(1);
        ++t.runs;
        // Long enough for the threads to overlap, so that a missing wait shows.
        std::this_thread::sleep_for(std::chrono::microseconds(20));
        t.end = clock.fetch_add(1);
    });
    const auto endOf = [&](size_t stage, size_t share) {  // when a share's last block ended
        uint64_t end = 0;
        for (uint32_t b = 0; b < blocks[stage * shares + share]; ++b) {
            end = std::max(end, times[(stage * shares + share) * kMaxBlocks + b].end);
        }
        return end;
    };
    for (size_t t = 0; t < kStages; ++t) {
        for (size_t s = 0; s < shares; ++s) {
            for (uint32_t b = 0; b < blocks[t * shares + s]; ++b) {
                const Times& block = times[(t * shares + s) * kMaxBlocks + b];
                EXPECT_EQ(block.runs, 1) << "stage " << t << " share " << s << " block " << b;
                for (size_t o = 0; o < shares && t >= 1; ++o) {
                    const bool waits = !withDependencies || ((waitFor[t * shares + s] >> o) & 1);
                    if (waits) {
                        EXPECT_LT(endOf(t - 1, o), block.start) << t << " " << s << " " << o;
                    }
                    for (size_t earlier = 0; earlier + 2 <= t; ++earlier) {
                        EXPECT_LT(endOf(earlier, o), block.start)
                            << t << " " << earlier << " " << o;
                    }
                }
            }
        }
    }
}

TEST(StageRunnerTest, BarrierBetweenStages) {
    for (const int threads : {1, 2, 3, 8}) {
        SCOPED_TRACE(threads);
        RunAndCheck(threads, false);
    }
}

TEST(StageRunnerTest, SharesWaitForWhatTheyDependOn) {
    for (const int threads : {2, 3, 8}) {
        SCOPED_TRACE(threads);
        RunAndCheck(threads, true);
    }
}

// A stage waits for every stage before the one before, not just for the one two back: here
// stage 2 is empty, so a stage 3 that waited only for stage 1 would run beside the slow block of
// stage 0, which no share after it names.
TEST(StageRunnerTest, WaitsForAllEarlierStagesNotJustTwoBack) {
    constexpr int kThreads = 3;
    // Stage 0: a slow block in share 0; stage 1: a block in share 1; stage 2: none; stage 3: a
    // block in share 1.
    const std::vector<uint32_t> blocks{1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0};
    const std::vector<uint64_t> waitFor(blocks.size(), 0);  // no share names another
    std::atomic<uint64_t> clock{1};
    uint64_t slowEnd = 0;
    uint64_t lastStart = 0;
    StageRunner runner;
    runner.Run(blocks, waitFor, kThreads, [&](size_t stage, uint32_t, uint32_t) {
        if (stage == 0) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            slowEnd = clock.fetch_add(1);
        } else if (stage == 3) {
            lastStart = clock.fetch_add(1);
        }
    });
    EXPECT_LT(slowEnd, lastStart);
}

// Asking for more threads than TBB lends (here one: only the caller) still finishes: the
// caller takes the shares of the helpers that never start.
TEST(StageRunnerTest, FinishesWithFewerThreadsThanShares) {
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    RunAndCheck(6, false);
    RunAndCheck(6, true);
}

}  // namespace
}  // namespace rtrt::physics
