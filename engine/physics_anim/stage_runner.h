#pragma once
// Runs a sequence of stages on several threads, each stage a set of blocks that may run at once,
// with a barrier between stages. The threads stay in the run and spin from one stage to the next
// instead of going back to the scheduler: the contact solver has a few hundred short stages per
// step (its colours times its iterations), and a parallel_for each would pay a worker wake-up
// each time.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
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

    // Calls work(stage, share, block) once for every block of every share of every stage, all
    // blocks of a stage before any of the next; share s of stage t has
    // blocksPerShare[t * shares + s] blocks. threads <= 1 runs everything in order on the calling
    // thread.
    //
    // There are as many shares as threads, and each thread works through the same share in every
    // stage: the solver cuts each colour into shares in region order, so a body's cache line stays
    // with one core from colour to colour instead of moving at every stage. Until every thread has
    // joined the run, a thread that runs out also takes blocks of the others' shares (a helper
    // may start late, or never, leaving its task to the caller's wait); once all are in, each
    // keeps to its own, as taking another's blocks would move their rows and bodies to its core.
    // Any thread may still run any block, so work must not depend on which thread runs it.
    //
    // Never deadlocks, however many threads TBB actually lends: a thread waits only for blocks
    // that other threads have already claimed and are running, or for the shares of threads that
    // have joined and so will run them.
    template <typename Work>
    void Run(std::span<const uint32_t> blocksPerShare, int threads, const Work& work) {
        const auto shares = static_cast<uint32_t>(std::max(threads, 1));
        const size_t stages = blocksPerShare.size() / shares;
        if (threads <= 1) {
            for (size_t t = 0; t < stages; ++t) {
                for (uint32_t b = 0; b < blocksPerShare[t]; ++b) work(t, 0u, b);
            }
            return;
        }
        if (claimedCapacity_ < stages * shares) {
            claimed_ = std::make_unique<Counter[]>(stages * shares);
            claimedCapacity_ = stages * shares;
        }
        if (completedCapacity_ < stages) {
            completed_ = std::make_unique<Counter[]>(stages);
            released_ = std::make_unique<Counter[]>(stages);
            completedCapacity_ = stages;
        }
        for (size_t i = 0; i < stages * shares; ++i) {
            claimed_[i].value.store(0, std::memory_order_relaxed);
        }
        for (size_t t = 0; t < stages; ++t) {
            completed_[t].value.store(0, std::memory_order_relaxed);
            released_[t].value.store(0, std::memory_order_relaxed);
        }
        std::atomic<uint32_t> nextHome{0};
        const auto participate = [&] {
            const uint32_t home = nextHome.fetch_add(1, std::memory_order_relaxed) % shares;
            bool everyoneIn = false;
            for (size_t t = 0; t < stages; ++t) {
                const uint32_t* blocks = blocksPerShare.data() + t * shares;
                uint32_t stageBlocks = 0;
                for (uint32_t s = 0; s < shares; ++s) stageBlocks += blocks[s];
                std::atomic<uint32_t>& completed = completed_[t].value;
                uint32_t done = 0;
                for (uint32_t k = 0; k < shares; ++k) {
                    const uint32_t share = (home + k) % shares;
                    std::atomic<uint32_t>& claimed = claimed_[t * shares + share].value;
                    // Another share's counter is read before it is bumped: most are done by
                    // then, and a read leaves the line shared where a bump would take it away
                    // from every other thread that checks it.
                    if (k > 0) {
                        if (!everyoneIn) {
                            everyoneIn = nextHome.load(std::memory_order_relaxed) >= shares;
                        }
                        if (everyoneIn) break;
                        if (claimed.load(std::memory_order_relaxed) >= blocks[share]) continue;
                    }
                    for (uint32_t b = claimed.fetch_add(1, std::memory_order_relaxed);
                         b < blocks[share]; b = claimed.fetch_add(1, std::memory_order_relaxed)) {
                        work(t, share, b);
                        ++done;
                    }
                }
                if (stageBlocks == 0) continue;
                // One count per thread and stage, once it has nothing left to claim; the thread
                // whose count completes the stage raises its flag. The threads spin on the flag,
                // which is written once, not on the count: each bump would otherwise have to
                // take the line back from every spinning core. acq_rel on the count and release
                // on the flag: the next stage's readers see every thread's writes.
                std::atomic<uint32_t>& released = released_[t].value;
                if (done > 0 &&
                    completed.fetch_add(done, std::memory_order_acq_rel) + done == stageBlocks) {
                    released.store(1, std::memory_order_release);
                }
                for (int spins = 0; released.load(std::memory_order_acquire) == 0; ++spins) {
                    Pause(spins);
                }
            }
        };
        tbb::task_group helpers;
        for (uint32_t t = 1; t < shares; ++t) helpers.run(participate);
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

    std::unique_ptr<Counter[]> claimed_;    // per stage and share
    std::unique_ptr<Counter[]> completed_;  // per stage: blocks done
    std::unique_ptr<Counter[]> released_;   // per stage: raised when every block is done
    size_t claimedCapacity_ = 0;
    size_t completedCapacity_ = 0;
};

}  // namespace rtrt::physics
