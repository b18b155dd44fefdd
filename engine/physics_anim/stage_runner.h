#pragma once
// Runs a sequence of stages on several threads, each stage a set of blocks that may run at once,
// with a barrier between stages. The threads stay in the run and spin from one stage to the next
// instead of going back to the scheduler: the contact solver has a few hundred short stages per
// step (its colours times its iterations), and a parallel_for each would pay a worker wake-up
// each time.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <thread>

#if defined(__x86_64__) || defined(_M_X64)
#include <immintrin.h>
#endif

namespace rtrt::physics {

class StageRunner {
  public:
    // The threads a run may use: TBB's arena, within any global_control limit.
    static int AvailableThreads() {
        const auto limit = static_cast<int>(
            tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
        return std::max(1, std::min(tbb::this_task_arena::max_concurrency(), limit));
    }

    // Calls work(stage, block) once for every block of every stage, all blocks of a stage before
    // any of the next. Blocks are claimed by whichever thread is free, so work must not depend
    // on which thread runs it. threads <= 1 runs everything in order on the calling thread.
    //
    // Never deadlocks, however many threads TBB actually lends: a thread waits only for blocks
    // that other threads have already claimed and are running, and a helper that starts late
    // (or never, leaving its task to the caller's wait) finds the finished stages empty.
    template <typename Work>
    void Run(std::span<const uint32_t> blocksPerStage, int threads, const Work& work) {
        const size_t stages = blocksPerStage.size();
        if (threads <= 1) {
            for (size_t s = 0; s < stages; ++s) {
                for (uint32_t b = 0; b < blocksPerStage[s]; ++b) work(s, b);
            }
            return;
        }
        if (capacity_ < stages) {
            claimed_ = std::make_unique<Counter[]>(stages);
            completed_ = std::make_unique<Counter[]>(stages);
            capacity_ = stages;
        }
        for (size_t s = 0; s < stages; ++s) {
            claimed_[s].value.store(0, std::memory_order_relaxed);
            completed_[s].value.store(0, std::memory_order_relaxed);
        }
        const auto participate = [&] {
            for (size_t s = 0; s < stages; ++s) {
                const uint32_t blocks = blocksPerStage[s];
                std::atomic<uint32_t>& claimed = claimed_[s].value;
                std::atomic<uint32_t>& completed = completed_[s].value;
                for (uint32_t b = claimed.fetch_add(1, std::memory_order_relaxed); b < blocks;
                     b = claimed.fetch_add(1, std::memory_order_relaxed)) {
                    work(s, b);
                    // Release: the next stage's readers see this block's writes.
                    completed.fetch_add(1, std::memory_order_acq_rel);
                }
                for (int spins = 0; completed.load(std::memory_order_acquire) < blocks; ++spins) {
                    Pause(spins);
                }
            }
        };
        tbb::task_group helpers;
        for (int t = 1; t < threads; ++t) helpers.run(participate);
        participate();
        helpers.wait();
    }

  private:
    struct alignas(64) Counter {
        std::atomic<uint32_t> value{0};
    };

    // Spins briefly, then yields, so that a machine with fewer cores than threads still moves.
    static void Pause(int spins) {
        if (spins < 256) {
#if defined(__x86_64__) || defined(_M_X64)
            _mm_pause();
#endif
        } else {
            std::this_thread::yield();
        }
    }

    std::unique_ptr<Counter[]> claimed_;
    std::unique_ptr<Counter[]> completed_;
    size_t capacity_ = 0;
};

}  // namespace rtrt::physics
