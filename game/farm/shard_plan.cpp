#include "game/farm/shard_plan.h"

#include <algorithm>

namespace rtrt {

std::vector<std::vector<FrameRange>> PlanShards(const std::vector<int>& frames, int shards) {
    std::vector<std::vector<FrameRange>> tasks;
    const size_t n = frames.size();
    const size_t k = std::min(n, size_t(std::max(shards, 1)));
    for (size_t t = 0; t < k; ++t) {
        // Task t takes frames [t n / k, (t + 1) n / k) of the list.
        const size_t begin = t * n / k, end = (t + 1) * n / k;
        std::vector<FrameRange> ranges;
        for (size_t i = begin; i < end; ++i) {
            if (!ranges.empty() && ranges.back().end == frames[i])
                ++ranges.back().end;
            else
                ranges.push_back({frames[i], frames[i] + 1});
        }
        tasks.push_back(std::move(ranges));
    }
    return tasks;
}

}  // namespace rtrt
