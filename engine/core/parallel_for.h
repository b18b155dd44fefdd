#pragma once
// Host-side data parallelism (TBB). The CUDA back end launches kernels instead; both run the same
// RT_HD body per item.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>

namespace rtrt {

template <typename Body>
void ParallelFor(size_t begin, size_t end, size_t grain, const Body& body) {
    tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, grain),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t i = r.begin(); i != r.end(); ++i) body(i);
                      });
}

}  // namespace rtrt
