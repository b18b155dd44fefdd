// The accuracy benchmark's measures on images small enough to work out by hand.
#include "bench/accuracy/image_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rtrt {
namespace {

Image Pixels(std::initializer_list<vec3> pixels) {
    Image image(uint32_t(pixels.size()), 1);
    image.pixels.assign(pixels);
    return image;
}

TEST(ImageMetrics, RmseAndPsnrOfHalfWhiteAgainstBlack) {
    // One pixel off by 1 in every channel, one equal: MSE = 3 / 6, RMSE = sqrt(0.5).
    const Image a = Pixels({vec3(0.0f), vec3(1.0f)});
    const Image b = Pixels({vec3(0.0f), vec3(0.0f)});
    EXPECT_DOUBLE_EQ(Rmse(a, b), std::sqrt(0.5));
    // PSNR = 20 log10(1 / sqrt(0.5)) = 10 log10(2).
    EXPECT_NEAR(Psnr(Rmse(a, b)), 10.0 * std::log10(2.0), 1e-12);
}

TEST(ImageMetrics, OneChannelOffByAQuarter) {
    // Squared error 1/16 in one channel of one pixel out of 2: MSE = (1/16) / 6.
    const Image a = Pixels({vec3(0.5f, 0.25f, 0.0f), vec3(0.25f)});
    const Image b = Pixels({vec3(0.5f, 0.5f, 0.0f), vec3(0.25f)});
    EXPECT_DOUBLE_EQ(Rmse(a, b), std::sqrt(1.0 / 96.0));
}

TEST(ImageMetrics, ColoursAreClampedAsDisplayedBeforeComparing) {
    const Image a = Pixels({vec3(2.0f, -1.0f, 0.5f)});
    const Image b = Pixels({vec3(1.0f, 0.0f, 0.5f)});
    EXPECT_EQ(Rmse(a, b), 0.0);
    EXPECT_TRUE(std::isinf(Psnr(0.0)));
    EXPECT_EQ(DifferenceImage(a, b).pixels[0], vec3(0.0f));
}

// A NaN channel (in either image) is as far off as a channel can be: it had made the RMSE NaN,
// the PSNR infinite (reported as a perfect match) and no outlier.
TEST(ImageMetrics, ANaNChannelDiffersByOne) {
    const float nan = std::nanf("");
    const Image a = Pixels({vec3(0.5f, nan, 0.5f), vec3(0.25f)});
    const Image b = Pixels({vec3(0.5f), vec3(0.25f)});
    EXPECT_DOUBLE_EQ(Rmse(a, b), std::sqrt(1.0 / 6.0));
    EXPECT_DOUBLE_EQ(Rmse(b, a), std::sqrt(1.0 / 6.0));
    EXPECT_EQ(OutlierRate(a, b, 0.1f), 0.5);
    EXPECT_EQ(DifferenceImage(a, b).pixels[0], vec3(0.0f, 1.0f, 0.0f));
    // Infinities are displayed as the clamp shows them.
    const float inf = HUGE_VALF;
    EXPECT_EQ(Rmse(Pixels({vec3(inf, -inf, 0.0f)}), Pixels({vec3(1.0f, 0.0f, 0.0f)})), 0.0);
}

TEST(ImageMetrics, ImagesOfOneCountButAnotherShapeAreRefused) {
    EXPECT_THROW(Rmse(Image(2, 1), Image(1, 2)), std::invalid_argument);
}

TEST(ImageMetrics, OutlierRateCountsPixelsWithAnyChannelBeyondTheThreshold) {
    const Image ref = Pixels({vec3(0.5f), vec3(0.5f), vec3(0.5f), vec3(0.5f)});
    const Image img =
        Pixels({vec3(0.5f), vec3(0.55f), vec3(0.5f, 0.5f, 0.75f), vec3(0.0f, 0.5f, 0.5f)});
    EXPECT_DOUBLE_EQ(OutlierRate(img, ref, 0.1f), 0.5);  // the last two
    EXPECT_DOUBLE_EQ(OutlierRate(img, ref, 0.3f), 0.25);
}

TEST(ImageMetrics, MismatchRateComparesPrimaryObjects) {
    EXPECT_DOUBLE_EQ(MismatchRate({0, 1, 2, 3}, {0, 1, 3, 3}), 0.25);
    EXPECT_DOUBLE_EQ(MismatchRate({0, 0}, {1, 2}), 1.0);
    EXPECT_THROW(MismatchRate({0}, {0, 1}), std::invalid_argument);
}

TEST(ImageMetrics, DifferenceImageIsTheAbsoluteDifference) {
    const Image d =
        DifferenceImage(Pixels({vec3(0.25f, 0.75f, 0.5f)}), Pixels({vec3(0.75f, 0.25f, 0.5f)}));
    EXPECT_EQ(d.pixels[0], vec3(0.5f, 0.5f, 0.0f));
}

}  // namespace
}  // namespace rtrt
