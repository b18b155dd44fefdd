// StageRunner: every block of every share runs exactly once, a stage's blocks all finish before
// the next stage starts, a run completes whether or not TBB lends the threads asked for, and once
// every thread has joined, each share stays with one thread.
#include "engine/physics_anim/stage_runner.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

namespace rtrt::physics {
namespace {

// Stages of varying size, some with empty shares; records each block's runs and the number of
// blocks of earlier stages that had finished when it started.
void RunAndCheck(int threads) {
    constexpr size_t kStages = 40;
    const auto shares = static_cast<size_t>(std::max(threads, 1));
    std::vector<uint32_t> blocks(kStages * shares);
    std::vector<uint32_t> stageBegin(kStages + 1, 0);
    for (size_t t = 0; t < kStages; ++t) {
        uint32_t total = 0;
        for (size_t s = 0; s < shares; ++s) {
            blocks[t * shares + s] = static_cast<uint32_t>((t * 7 + s * 3) % 5);  // 0 to 4
            total += blocks[t * shares + s];
        }
        stageBegin[t + 1] = stageBegin[t] + total;
    }
    const uint32_t total = stageBegin[kStages];
    std::vector<std::atomic<int>> runs(kStages * shares * 8);
    std::vector<uint32_t> finishedBefore(kStages * shares * 8, 0);
    std::atomic<uint32_t> finished{0};
    StageRunner runner;
    runner.Run(blocks, threads, [&](size_t stage, uint32_t share, uint32_t block) {
        ASSERT_LT(share, shares);
        ASSERT_LT(block, blocks[stage * shares + share]);
        const size_t id = (stage * shares + share) * 8 + block;
        finishedBefore[id] = finished.load();
        runs[id].fetch_add(1);
        // Long enough for the threads to overlap, so that a missing wait shows.
        std::this_thread::sleep_for(std::chrono::microseconds(20));
        finished.fetch_add(1);
    });
    EXPECT_EQ(finished.load(), total);
    for (size_t t = 0; t < kStages; ++t) {
        for (size_t s = 0; s < shares; ++s) {
            for (uint32_t b = 0; b < blocks[t * shares + s]; ++b) {
                const size_t id = (t * shares + s) * 8 + b;
                EXPECT_EQ(runs[id].load(), 1) << "stage " << t << " share " << s << " block " << b;
                EXPECT_GE(finishedBefore[id], stageBegin[t]) << "stage " << t << " began early";
            }
        }
    }
}

TEST(StageRunnerTest, EveryBlockOnceInStageOrder) {
    for (const int threads : {1, 2, 3, 8}) {
        SCOPED_TRACE(threads);
        RunAndCheck(threads);
    }
}

// Asking for more threads than TBB lends (here one: only the caller) still finishes: the
// caller takes the shares of the helpers that never start.
TEST(StageRunnerTest, FinishesWithFewerThreadsThanShares) {
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    RunAndCheck(6);
}

// Shares of unequal work, so that a thread with a light share runs out early: once every thread
// has joined (long before the last stages here), it waits instead of taking blocks of a heavier
// share, whose rows and bodies would then move to its core.
TEST(StageRunnerTest, EachShareStaysWithOneThreadOnceAllHaveJoined) {
    // As many shares as TBB lends threads, so that all of them join.
    const int threads = std::min(4, StageRunner::AvailableThreads());
    if (threads < 2) GTEST_SKIP() << "needs two threads";
    const auto shares = static_cast<size_t>(threads);
    constexpr size_t kStages = 60;
    constexpr size_t kLastStages = 20;
    std::vector<uint32_t> blocks(kStages * shares);
    for (size_t t = 0; t < kStages; ++t) {
        for (size_t s = 0; s < shares; ++s) blocks[t * shares + s] = s == 0 ? 6 : 1;
    }
    std::mutex mutex;
    std::map<uint32_t, std::vector<std::thread::id>> threadsOfShare;
    StageRunner runner;
    runner.Run(blocks, threads, [&](size_t stage, uint32_t share, uint32_t) {
        std::this_thread::sleep_for(std::chrono::microseconds(50));
        if (stage < kStages - kLastStages) return;
        const std::lock_guard<std::mutex> lock(mutex);
        threadsOfShare[share].push_back(std::this_thread::get_id());
    });
    ASSERT_EQ(threadsOfShare.size(), shares);
    for (const auto& [share, ids] : threadsOfShare) {
        for (const std::thread::id id : ids) EXPECT_EQ(id, ids.front()) << "share " << share;
    }
}

}  // namespace
}  // namespace rtrt::physics
