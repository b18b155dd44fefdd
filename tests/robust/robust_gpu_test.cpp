// The robust suite's shared cases on the GPU (label gpu): the evaluators of cases.h run in
// kernels compiled as the renderer's (gpu_runner.cu) and must meet the same expected values as on
// the CPU. Skipped where no CUDA device is usable.
#include "engine/render_rt/renderer.h"
#include "tests/robust/contact_checks.h"
#include "tests/robust/gpu_runner.h"
#include "tests/robust/slab_checks.h"
#include "tests/robust/spawn_checks.h"
#include "tests/robust/sphere_checks.h"
#include "tests/robust/tlas_checks.h"
#include "tests/robust/traversal_checks.h"
#include "tests/robust/triangle_checks.h"
#include "tests/robust/watertight_checks.h"

namespace rtrt::robust {
namespace {

class GpuRobust : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string why;
        if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    }
    GpuRunner run_;
};

TEST_F(GpuRobust, Watertight) { CheckWatertightAll(run_); }
TEST_F(GpuRobust, SlabCases) { CheckSlabCases(run_); }
TEST_F(GpuRobust, TriangleDirectionScale) { CheckTriangleDirectionScale(run_); }
TEST_F(GpuRobust, TriangleTMaxIdempotent) { CheckTriangleTMaxIdempotent(run_); }
TEST_F(GpuRobust, SphereCases) { CheckSphereCases(run_); }
TEST_F(GpuRobust, TraversalMatchesBruteForce) { CheckTraversalMatchesBruteForce(run_, 2'000'000); }
TEST_F(GpuRobust, BadRays) { CheckBadRays(run_); }
TEST_F(GpuRobust, SpawnFromFarSurfaces) { CheckSpawnFromFarPlanes(run_); }
TEST_F(GpuRobust, SpawnIntoFarObjects) { CheckSpawnIntoFarObjects(run_); }
TEST_F(GpuRobust, TlasDegenerateInputs) { CheckTlasDegenerateInputs(run_); }
TEST_F(GpuRobust, RaysStartingNearASurfaceFindIt) { CheckRaysStartingNearASurfaceFindIt(run_); }
TEST_F(GpuRobust, ContactShadowsAreDarkFromEveryLight) { CheckContactShadowsAreDark(run_); }
TEST_F(GpuRobust, HugeGroundSpheresCastTheShadowsOfAPlane) { CheckSmallBoxShadowsOnGrounds(run_); }

// Device code fuses a multiply-add only where asked (mul_add.h): otherwise where the compiler
// placed a computation would decide its last bits, and the traversal forms' frames would differ.
// (1 + 2^-13)(1 - 2^-13) - 1 is -2^-26 exactly with one rounding; the product alone rounds to 1.
TEST_F(GpuRobust, DeviceCodeFusesMultiplyAddsOnlyWhereAsked) {
    const auto [fused, plain] = MulAddOnGpu(1.0f + 0x1p-13f, 1.0f - 0x1p-13f, -1.0f);
    EXPECT_EQ(fused, -0x1p-26f);
    EXPECT_EQ(plain, 0.0f);
}

}  // namespace
}  // namespace rtrt::robust
