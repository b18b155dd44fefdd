// MulAdd on the host: a product and a sum, each rounded (the host compiles with
// -ffp-contract=off), so that host results stay what they were before the GPU asked for fused
// multiply-adds. The GPU's side: GpuRobust.DeviceCodeFusesMultiplyAddsOnlyWhereAsked.
#include "engine/core/mul_add.h"

#include <gtest/gtest.h>

#include "engine/core/affine.h"

namespace rtrt {
namespace {

// (1 + 2^-13)(1 - 2^-13) = 1 - 2^-26 rounds to 1, so the unfused result is 0 (fused: -2^-26).
TEST(MulAdd, RoundsTheProductOnTheHost) {
    volatile float a = 1.0f + 0x1p-13f, b = 1.0f - 0x1p-13f;
    EXPECT_EQ(MulAdd(a, b, -1.0f), 0.0f);
}

// The affine rows' dot products (the rays' transform into an instance) are MulAdds too.
TEST(MulAdd, AffineRowsRoundEveryProductOnTheHost) {
    Affine m = Affine::Identity();
    m.row[0] = vec4(1.0f + 0x1p-13f, 1.0f, 0.0f, 0.0f);
    EXPECT_EQ(m.Vector(vec3(1.0f - 0x1p-13f, -1.0f, 0.0f)).x, 0.0f);
}

}  // namespace
}  // namespace rtrt
