#pragma once
// Frames to render split into the tasks of a job array.
#include <vector>

#include "game/farm/farm_job.h"

namespace rtrt {

// FRAMES (ascending, no repeats) cut into at most SHARDS tasks of nearly equal frame counts (they
// differ by at most one), each a list of contiguous ranges in order. A first submission gives
// each task one range; a resubmission gives the missing frames, which may come in several runs.
std::vector<std::vector<FrameRange>> PlanShards(const std::vector<int>& frames, int shards);

}  // namespace rtrt
