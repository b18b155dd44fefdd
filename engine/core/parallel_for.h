#pragma once
// Data parallelism with one body for both back ends: ParallelFor runs body(i) for i in
// [begin, end) over TBB on the host; ParallelForCuda (parallel_for_cuda.h) runs the same body,
// one CUDA thread per index. Bodies that run on both are RT_HD function objects.
//
// In an arena of one thread (a small world's physics step runs in one, PhysicsWorld) the loop
// runs inline: TBB would still cut the range into tasks and pass each through its queue, for
// nothing (bench/results/inline-small-world-loops-vm-2026-12-05.txt).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <cstddef>

namespace rtrt {

template <typename Body>
void ParallelFor(size_t begin, size_t end, size_t grain, const Body& body) {
    if (tbb::this_task_arena::max_concurrency() == 1) {
        for (size_t i = begin; i < end; ++i) body(i);
        return;
    }
    tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, grain),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t i = r.begin(); i != r.end(); ++i) body(i);
                      });
}

// The same, with TBB's affinity partitioner: loops over the same range that share one partitioner
// run each chunk on the thread that ran it the last time, so that its data is still in that core's
// cache.
template <typename Body>
void ParallelFor(size_t begin, size_t end, size_t grain, tbb::affinity_partitioner& affinity,
                 const Body& body) {
    if (tbb::this_task_arena::max_concurrency() == 1) {
        for (size_t i = begin; i < end; ++i) body(i);
        return;
    }
    tbb::parallel_for(
        tbb::blocked_range<size_t>(begin, end, grain),
        [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i != r.end(); ++i) body(i);
        },
        affinity);
}

}  // namespace rtrt
