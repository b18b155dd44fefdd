// GPU images equal CPU images (the reference) within a stated tolerance, for every verification
// scene: RMSE <= 1/255 and at most 0.5% of pixels off by more than 4/255 in any channel. The two
// back ends run the same RT_HD code; the tolerance covers float rounding (the GPU contracts
// multiply-adds outside the watertight edge tests, and its powf/sqrtf round differently), which can
// flip a pixel on a silhouette or shadow edge. Label gpu: CI has no GPU and skips these.
#include <gtest/gtest.h>

#include "engine/render_rt/renderer.h"
#include "game/default_scene.h"
#include "game/scene_file.h"
#include "tests/test_util.h"

namespace rtrt {
namespace {

void ExpectGpuMatchesCpu(const RenderScene& scene, ViewMode view = ViewMode::kShaded) {
    std::string why;
    if (!CudaBackendAvailable(&why)) GTEST_SKIP() << why;
    RenderSettings s;
    s.width = 320;
    s.height = 240;
    s.maxDepth = scene.maxDepth;
    s.view = view;
    RenderStats cpuStats, gpuStats;
    const Image cpu = RenderRaw(scene, s, &cpuStats);
    const Image gpu = RenderRawCuda(scene, s, &gpuStats);
    double sum = 0.0;
    size_t outliers = 0;
    for (size_t i = 0; i < cpu.pixels.size(); ++i) {
        float worst = 0.0f;
        for (int c = 0; c < 3; ++c) {
            const float a = std::clamp(cpu.pixels[i][c], 0.0f, 1.0f);
            const float b = std::clamp(gpu.pixels[i][c], 0.0f, 1.0f);
            sum += double(a - b) * (a - b);
            worst = std::max(worst, std::abs(a - b));
        }
        outliers += worst > 4.0f / 255.0f;
    }
    const double rmse = std::sqrt(sum / (3.0 * cpu.pixels.size()));
    EXPECT_LE(rmse, 1.0 / 255.0);
    EXPECT_LE(double(outliers), 0.005 * cpu.pixels.size()) << outliers << " pixels differ";
    // Ray counts differ only where a pixel's path differs.
    EXPECT_NEAR(double(gpuStats.rays), double(cpuStats.rays), 0.005 * double(cpuStats.rays));
}

LoadedScene Asset(const std::string& name) {
    return LoadSceneFile(test::SourcePath("assets/scenes/" + name));
}

TEST(GpuVsCpu, DefaultScene) { ExpectGpuMatchesCpu(MakeDefaultScene()); }
TEST(GpuVsCpu, DefaultSceneNormals) { ExpectGpuMatchesCpu(MakeDefaultScene(), ViewMode::kNormals); }
TEST(GpuVsCpu, ReflectiveSphere) { ExpectGpuMatchesCpu(Asset("reflective_sphere.json").scene); }
TEST(GpuVsCpu, RefractiveSphere) { ExpectGpuMatchesCpu(Asset("refractive_sphere.json").scene); }

TEST(GpuVsCpu, TeapotShadow) {
    RTRT_REQUIRE_MODEL(teapot, "teapot.inc");
    ExpectGpuMatchesCpu(Asset("teapot_shadow.json").scene);
}

TEST(GpuVsCpu, FullDragon) {
    RTRT_REQUIRE_MODEL(dragon, "dragon_vrip.ply.gz");
    ExpectGpuMatchesCpu(Asset("dragon.json").scene);
}

}  // namespace
}  // namespace rtrt
