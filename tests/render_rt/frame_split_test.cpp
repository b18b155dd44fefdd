// FrameSplit: row bands that tile the frame in granules, equal at first, then following the
// tracers' measured speeds.
#include "engine/render_rt/split/frame_split.h"

#include <gtest/gtest.h>

#include <vector>

namespace rtrt {
namespace {

// Bands in order, from row 0 to the last, whole granules but for the last band's end.
void ExpectTiles(const std::vector<RowBand>& bands, uint32_t height) {
    uint32_t row = 0;
    for (const RowBand& b : bands) {
        EXPECT_EQ(b.begin, row);
        EXPECT_LE(b.begin, b.end);
        if (b.end != height) {
            EXPECT_EQ(b.end % FrameSplit::kRowGranule, 0u);
        }
        row = b.end;
    }
    EXPECT_EQ(row, height);
}

TEST(FrameSplit, OnePartIsTheWholeFrame) {
    const FrameSplit split(1);
    const std::vector<RowBand> bands = split.Bands(1080);
    ASSERT_EQ(bands.size(), 1u);
    EXPECT_EQ(bands[0].begin, 0u);
    EXPECT_EQ(bands[0].end, 1080u);
}

TEST(FrameSplit, StartsEqualAndTilesTheFrame) {
    const FrameSplit split(4);
    const std::vector<RowBand> bands = split.Bands(1080);  // 135 granules: 34, 34, 34, 33
    ASSERT_EQ(bands.size(), 4u);
    ExpectTiles(bands, 1080);
    EXPECT_EQ(bands[0].Rows(), 272u);
    EXPECT_EQ(bands[1].Rows(), 272u);
    EXPECT_EQ(bands[2].Rows(), 272u);
    EXPECT_EQ(bands[3].Rows(), 264u);
    for (uint32_t height : {0u, 1u, 7u, 8u, 9u, 31u, 33u, 721u})
        ExpectTiles(split.Bands(height), height);
}

TEST(FrameSplit, EveryPartGetsAGranuleWhileThereAreEnough) {
    FrameSplit split(3);
    const double ms[] = {1.0, 1000.0, 1000.0};  // the first part far faster
    for (int i = 0; i < 20; ++i) split.Report(split.Bands(240), ms);
    const std::vector<RowBand> bands = split.Bands(240);
    ExpectTiles(bands, 240);
    EXPECT_GE(bands[1].Rows(), FrameSplit::kRowGranule);
    EXPECT_GE(bands[2].Rows(), FrameSplit::kRowGranule);
    EXPECT_EQ(split.Bands(16)[2].Rows(), 0u);  // two granules for three parts
}

// A tracer twice as fast per row ends up with two thirds of the rows, after which the reported
// times are equal and the shares stay.
TEST(FrameSplit, SharesFollowSpeed) {
    FrameSplit split(2);
    const uint32_t height = 1200;
    for (int frame = 0; frame < 30; ++frame) {
        const std::vector<RowBand> bands = split.Bands(height);
        const double ms[] = {bands[0].Rows() * 0.001, bands[1].Rows() * 0.002};
        split.Report(bands, ms);
    }
    EXPECT_NEAR(split.Shares()[0], 2.0 / 3.0, 1e-3);
    const std::vector<RowBand> bands = split.Bands(height);
    EXPECT_NEAR(double(bands[0].Rows()), 800.0, 8.0);
    ExpectTiles(bands, height);
}

TEST(FrameSplit, UnmeasuredTimesLeaveTheShares) {
    FrameSplit split(2);
    const double zero[] = {0.0, 1.0};
    split.Report(split.Bands(1080), zero);
    EXPECT_EQ(split.Shares()[0], 0.5);
    const double wrongCount[] = {1.0};
    split.Report(split.Bands(1080), wrongCount);
    EXPECT_EQ(split.Shares()[1], 0.5);
}

}  // namespace
}  // namespace rtrt
