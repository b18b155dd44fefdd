#pragma once
// A stable parallel compaction: the indices i in [0, n) for which keep(i) holds, in increasing
// order, each handed to emit(i, position) with its position among them. The range is cut into
// fixed chunks that are counted, then written from their prefix sums, so the positions do not
// depend on the number of threads. Returns the number kept.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "engine/core/parallel_for.h"

namespace rtrt {

template <typename Keep, typename Emit>
uint32_t ParallelCompact(size_t n, std::vector<uint32_t>& chunkStarts, const Keep& keep,
                         const Emit& emit) {
    constexpr size_t kChunk = 2048;
    const size_t chunks = (n + kChunk - 1) / kChunk;
    chunkStarts.assign(chunks + 1, 0);
    ParallelFor(0, chunks, 1, [&](size_t chunk) {
        uint32_t count = 0;
        for (size_t i = chunk * kChunk; i < std::min(n, (chunk + 1) * kChunk); ++i)
            count += keep(i);
        chunkStarts[chunk + 1] = count;
    });
    for (size_t chunk = 0; chunk < chunks; ++chunk) chunkStarts[chunk + 1] += chunkStarts[chunk];
    ParallelFor(0, chunks, 1, [&](size_t chunk) {
        uint32_t position = chunkStarts[chunk];
        for (size_t i = chunk * kChunk; i < std::min(n, (chunk + 1) * kChunk); ++i)
            if (keep(i)) emit(i, position++);
    });
    return chunkStarts[chunks];
}

}  // namespace rtrt
