// Rounding-error helpers (pbrt-v4 section 6.8): exact neighbours and outward-rounded offsets.
#include "engine/core/float_bounds.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rtrt {
namespace {

TEST(FloatBounds, GammaIsTheStandardBound) {
    const float eps = std::numeric_limits<float>::epsilon() / 2;  // 2^-24
    EXPECT_EQ(kMachineEpsilon, eps);
    EXPECT_FLOAT_EQ(Gamma(3), 3 * eps / (1 - 3 * eps));
}

TEST(FloatBounds, NextFloatStepsOneUlp) {
    EXPECT_EQ(NextFloatUp(1.0f), std::nextafter(1.0f, 2.0f));
    EXPECT_EQ(NextFloatDown(1.0f), std::nextafter(1.0f, 0.0f));
    EXPECT_EQ(NextFloatUp(-1.0f), std::nextafter(-1.0f, 0.0f));
    // Zero of either sign steps to the smallest denormal, not to -0 or past it.
    EXPECT_EQ(NextFloatUp(-0.0f), std::numeric_limits<float>::denorm_min());
    EXPECT_EQ(NextFloatDown(0.0f), -std::numeric_limits<float>::denorm_min());
    EXPECT_EQ(NextFloatUp(kInfinity), kInfinity);
    EXPECT_EQ(NextFloatDown(-kInfinity), -kInfinity);
}

// The offset is |n| . pError along n, to w's side, then rounded one ulp further out.
TEST(FloatBounds, OffsetRayOriginLeavesTheErrorBoxOutward) {
    const vec3 p(1.0f, 2.0f, 3.0f), err(1e-3f, 0.0f, 0.0f), n(1.0f, 0.0f, 0.0f);
    const vec3 out = OffsetRayOrigin(p, err, n, vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(out.x, NextFloatUp(1.0f + 1e-3f));
    EXPECT_EQ(out.y, 2.0f);
    EXPECT_EQ(out.z, 3.0f);
    const vec3 in = OffsetRayOrigin(p, err, n, vec3(-1.0f, 0.5f, 0.0f));
    EXPECT_EQ(in.x, NextFloatDown(1.0f - 1e-3f));
}

}  // namespace
}  // namespace rtrt
