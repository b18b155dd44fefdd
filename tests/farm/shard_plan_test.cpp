#include "game/farm/shard_plan.h"

#include <gtest/gtest.h>

#include <numeric>

namespace rtrt {
namespace {

std::vector<int> Frames(int first, int end) {
    std::vector<int> frames(size_t(end - first));
    std::iota(frames.begin(), frames.end(), first);
    return frames;
}

TEST(ShardPlanTest, EqualSharesOfOneRange) {
    const auto tasks = PlanShards(Frames(0, 48), 4);
    ASSERT_EQ(tasks.size(), 4u);
    for (int t = 0; t < 4; ++t)
        EXPECT_EQ(tasks[t], (std::vector<FrameRange>{{12 * t, 12 * t + 12}}));
}

TEST(ShardPlanTest, SharesDifferByAtMostOneFrame) {
    const auto tasks = PlanShards(Frames(5, 15), 3);  // 10 frames: 3, 3, 4
    ASSERT_EQ(tasks.size(), 3u);
    EXPECT_EQ(tasks[0], (std::vector<FrameRange>{{5, 8}}));
    EXPECT_EQ(tasks[1], (std::vector<FrameRange>{{8, 11}}));
    EXPECT_EQ(tasks[2], (std::vector<FrameRange>{{11, 15}}));
}

TEST(ShardPlanTest, MissingFramesInSeveralRuns) {
    // What a resubmission sees: frames 3-5, 9 and 20-23 missing, cut into two tasks of four.
    const auto tasks = PlanShards({3, 4, 5, 9, 20, 21, 22, 23}, 2);
    ASSERT_EQ(tasks.size(), 2u);
    EXPECT_EQ(tasks[0], (std::vector<FrameRange>{{3, 6}, {9, 10}}));
    EXPECT_EQ(tasks[1], (std::vector<FrameRange>{{20, 24}}));
}

TEST(ShardPlanTest, NoMoreTasksThanFramesAndNoneForNoFrames) {
    EXPECT_EQ(PlanShards(Frames(0, 3), 10).size(), 3u);
    EXPECT_TRUE(PlanShards({}, 4).empty());
    const auto one = PlanShards(Frames(0, 7), 1);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(one[0], (std::vector<FrameRange>{{0, 7}}));
}

TEST(ShardPlanTest, EveryFrameExactlyOnce) {
    const std::vector<int> frames = {0, 1, 2, 7, 8, 13, 14, 15, 16, 40, 41, 99};
    for (int shards = 1; shards <= 14; ++shards) {
        std::vector<int> covered;
        for (const auto& task : PlanShards(frames, shards))
            for (const FrameRange& r : task)
                for (int f = r.first; f < r.end; ++f) covered.push_back(f);
        EXPECT_EQ(covered, frames) << shards << " shards";
    }
}

}  // namespace
}  // namespace rtrt
