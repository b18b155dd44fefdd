// The robust suite's shared cases on the GPU (label gpu): the evaluators of cases.h run in
// kernels compiled by nvcc with default contraction (gpu_runner.cu) and must meet the same
// expected values as on the CPU. Skipped where no CUDA device is usable.
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

}  // namespace
}  // namespace rtrt::robust
