#pragma once
// Runs a sequence of stages on several threads, each stage a set of blocks that may run at once,
// each after what it depends on in the stages before it (see Run). The threads stay in the run and
// spin from one stage to the next instead of going back to the scheduler: the contact solver has a
// few hundred short stages per step (its colours times its iterations), and a parallel_for each
// would pay a worker wake-up each time.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <memory>
#include <span>
#include <thread>
#include <vector>

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

    // Calls work(stage, share, block) once for every block of every share of every stage; share
    // s of stage t has blocksPerShare[t * shares + s] blocks. threads <= 1 runs everything in
    // order on the calling thread.
    //
    // Order: with waitFor empty, all blocks of a stage finish before any of the next starts.
    // Otherwise bit s' of waitFor[t * shares + s] says that share s of stage t must wait for
    // share s' of stage t - 1 (the shares whose data it touches), and it also waits for every
    // block of every stage before t - 1: so a share waits only for its neighbours instead of for
    // the slowest thread, and still never runs beside a block of an earlier stage that touches
    // its data. (Waiting for stage t - 2 alone is not enough: a finished stage t - 2 does not
    // mean a finished t - 3.)
    //
    // There are as many shares as threads (at most 64), and each thread works through the same
    // share in every stage before it takes blocks of the others' (when it runs out, or a helper is
    // late): the solver cuts each colour into shares by region, so a body's cache line stays with
    // one core from colour to colour instead of moving at every stage. Any thread may still run
    // any block, so work must not depend on which thread runs it.
    //
    // Never deadlocks, however many threads TBB actually lends: a thread claims blocks of stage t
    // only once it has seen every block of the stages before it claimed, so it waits only for
    // blocks that other threads have claimed and are running (themselves waiting only for earlier
    // ones), and the share of a helper that starts late (or never, leaving its task to the
    // caller's wait) is taken by the others.
    template <typename Work>
    void Run(std::span<const uint32_t> blocksPerShare, std::span<const uint64_t> waitFor,
             int threads, const Work& work) {
        const auto shares = static_cast<uint32_t>(std::clamp(threads, 1, kMaxShares));
        const size_t stages = blocksPerShare.size() / shares;
        if (shares == 1) {
            for (size_t t = 0; t < stages; ++t) {
                for (uint32_t b = 0; b < blocksPerShare[t]; ++b) work(t, 0u, b);
            }
            return;
        }
        const size_t cells = stages * shares;
        if (capacity_ < cells) {
            claimed_ = std::make_unique<Counter[]>(cells);
            completed_ = std::make_unique<Counter[]>(cells);
            capacity_ = cells;
        }
        if (stageCapacity_ < stages) {
            stageCompleted_ = std::make_unique<Counter[]>(stages);
            stageCapacity_ = stages;
        }
        stageBlocks_.assign(stages, 0);
        for (size_t i = 0; i < cells; ++i) {
            claimed_[i].value.store(0, std::memory_order_relaxed);
            completed_[i].value.store(0, std::memory_order_relaxed);
            stageBlocks_[i / shares] += blocksPerShare[i];
        }
        for (size_t t = 0; t < stages; ++t) {
            stageCompleted_[t].value.store(0, std::memory_order_relaxed);
        }
        const auto stageDone = [&](size_t t) {
            return stageCompleted_[t].value.load(std::memory_order_acquire) >= stageBlocks_[t];
        };
        // doneBelow: the caller's knowledge that every stage below it is done (it only grows).
        const auto ready = [&](size_t t, uint32_t share, size_t& doneBelow) {
            for (; doneBelow + 1 < t; ++doneBelow) {
                if (!stageDone(doneBelow)) return false;
            }
            if (t == 0) return true;
            if (waitFor.empty()) return stageDone(t - 1);
            for (uint64_t mask = waitFor[t * shares + share]; mask != 0; mask &= mask - 1) {
                const size_t cell =
                    (t - 1) * shares + static_cast<uint32_t>(std::countr_zero(mask));
                if (completed_[cell].value.load(std::memory_order_acquire) < blocksPerShare[cell]) {
                    return false;
                }
            }
            return true;
        };
        std::atomic<uint32_t> nextHome{0};
        const auto participate = [&] {
            const uint32_t home = nextHome.fetch_add(1, std::memory_order_relaxed) % shares;
            size_t doneBelow = 0;
            for (size_t t = 0; t < stages; ++t) {
                for (uint32_t k = 0; k < shares; ++k) {
                    const uint32_t share = (home + k) % shares;
                    const size_t cell = t * shares + share;
                    bool isReady = false;
                    for (uint32_t b = claimed_[cell].value.fetch_add(1, std::memory_order_relaxed);
                         b < blocksPerShare[cell];
                         b = claimed_[cell].value.fetch_add(1, std::memory_order_relaxed)) {
                        for (int spins = 0; !isReady && !(isReady = ready(t, share, doneBelow));
                             ++spins) {
                            Pause(spins);
                        }
                        work(t, share, b);
                        // Release: the readers of the next stages see this block's writes.
                        completed_[cell].value.fetch_add(1, std::memory_order_acq_rel);
                        stageCompleted_[t].value.fetch_add(1, std::memory_order_acq_rel);
                    }
                }
            }
        };
        tbb::task_group helpers;
        for (uint32_t t = 1; t < shares; ++t) helpers.run(participate);
        participate();
        helpers.wait();
    }

    static constexpr int kMaxShares = 64;  // a bit each in waitFor

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

    std::unique_ptr<Counter[]> claimed_;    // per stage and share
    std::unique_ptr<Counter[]> completed_;  // per stage and share
    std::unique_ptr<Counter[]> stageCompleted_;
    std::vector<uint32_t> stageBlocks_;
    size_t capacity_ = 0;
    size_t stageCapacity_ = 0;
};

}  // namespace rtrt::physics
