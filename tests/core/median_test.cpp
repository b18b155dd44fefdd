// The median every benchmark reports.
#include <gtest/gtest.h>

#include "engine/core/timer.h"

namespace rtrt {
namespace {

TEST(Median, OfAnOddCountIsTheMiddleValue) {
    EXPECT_EQ(Median({3.0, 1.0, 2.0}), 2.0);
    EXPECT_EQ(Median({5.0}), 5.0);
    EXPECT_EQ(Median({}), 0.0);
}

// Of an even count the upper middle value had been reported: of two runs, the slower one.
TEST(Median, OfAnEvenCountIsTheMeanOfTheTwoMiddleValues) {
    EXPECT_EQ(Median({181.6, 215.7}), 0.5 * (181.6 + 215.7));
    EXPECT_EQ(Median({4.0, 1.0, 3.0, 2.0}), 2.5);
    EXPECT_EQ(Median({7.0, 7.0, 1.0, 9.0}), 7.0);
    EXPECT_EQ(Median({2.0, 2.0, 2.0, 8.0, 1.0, 9.0}), 2.0);
}

}  // namespace
}  // namespace rtrt
